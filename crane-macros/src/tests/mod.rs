//! Unit tests of the stages, on `proc_macro2` tokens (outside the compiler).

mod errors;
mod ir;
mod minimal;
mod parse;
mod snapshot;

use proc_macro2::TokenStream;

/// The declaration of sect. 5.1 (eqs. 25-35), as source text so that the
/// error tests can break it in one place.
pub(crate) const NAVY: &str = r#"
    /// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
    pub struct NavyPlanar {
        params { m_l = 100.0, J1 = 0.1, J2 = 0.1, r1 = 0.1, r2 = 0.1,
                 alpha = PI / 3.0, l = 10.0, g = 9.81 }
        robot  [L1, L2, L0, x0, z0]      // p: the first n-a coordinates
        load   [x, z]                    // x: outputs, prescribed by gamma(t)
        inputs [u1, u2]
        kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }
        constraints {
            #[rope(N1 = L1)]
            rope1: 0.5*((x0 + l*sin(alpha))^2 + (z0 + l*cos(alpha))^2 - L1^2),
            rope0: 0.5*(x0^2 + z0^2 - L0^2),
            #[rope(N2 = L2 - L0)]
            hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L2 - L0)^2),
        }
    }
"#;

/// The minimal coordinates of sect. 5.1.2 (eqs. 36-40): `mu = [beta, gamma,
/// theta, L]`, `mu1 = [beta, gamma]`, `mu2 = [theta, L]`.
pub(crate) const MINIMAL: &str = r#"
        minimal [beta, gamma | theta, L] {
            let d = l*sin(gamma - beta)/sin(gamma);   // L0: pulley to boom tip P
            L1 = l*sin(beta)/sin(gamma);  L2 = d + L;  L0 = d;
            x0 = -d*sin(alpha - beta);    z0 = -d*cos(alpha - beta);
            x  = x0 + L*sin(theta);       z  = z0 - L*cos(theta);
        }
"#;

/// The declaration of sect. 5.1 with the `minimal` block of sect. 5.1.2.
pub(crate) fn navy_minimal_source() -> String {
    // before the closing brace of the struct
    let end = NAVY.trim_end().len() - 1;
    let (head, tail) = NAVY.split_at(NAVY[..end].trim_end().len());
    format!("{head}{MINIMAL}{tail}")
}

/// Tokens of `source`.
pub(crate) fn tokens(source: &str) -> TokenStream {
    match source.parse() {
        Ok(tokens) => tokens,
        Err(error) => panic!("test input does not lex: {error}"),
    }
}

/// The declaration of sect. 5.1.
pub(crate) fn navy_planar() -> TokenStream {
    tokens(NAVY)
}

/// Pretty-prints an expansion (which must be a valid file).
pub(crate) fn pretty(tokens: TokenStream) -> String {
    match syn::parse2::<syn::File>(tokens.clone()) {
        Ok(file) => prettyplease::unparse(&file),
        Err(error) => panic!("expansion does not parse: {error}\n{tokens}"),
    }
}
