//! Checks of the `sample` section: the box the generated self-test draws its
//! random points from.

use proc_macro2::Ident;

use super::resolve::{Lowerer, Place};
use crate::model::SelfTest;
use crate::parse::Expr;

/// Check the `sample` section: a constant range for every coordinate and,
/// when the model has a minimal map, for every minimal coordinate too, so
/// that the self-test always checks the map (a box for `mu` cannot be
/// derived reliably from the box for `q`: `phi` has several inverse branches
/// and its angles wrap).
pub(super) fn check_sample(
    section: &crate::parse::Section<Vec<crate::parse::SampleDecl>>,
    coords: &[Ident],
    mu: Option<&[Ident]>,
    lower: &mut Lowerer,
) -> Option<SelfTest> {
    let mut q_ranges: Vec<Option<(Expr, Expr)>> = vec![None; coords.len()];
    let mut mu_ranges: Vec<Option<(Expr, Expr)>> = vec![None; mu.map_or(0, <[Ident]>::len)];
    for item in &section.body {
        let low = lower.lower(&item.low, Place::ParamDefault);
        let high = lower.lower(&item.high, Place::ParamDefault);
        let value = |id: Option<crate::expr::Id>, lower: &Lowerer| id.and_then(|id| lower.arena.as_const(id));
        if let (Some(low), Some(high)) = (value(low, lower), value(high, lower))
            && !(low < high)
        {
            let (name, low_text, high_text) = (&item.name, &item.low, &item.high);
            let message = if low == high {
                format!(
                    "the range of `{name}` in `sample` is empty ({low_text} .. {high_text}): the self-test draws \
                     from `low .. high` with low < high"
                )
            } else {
                format!(
                    "the range of `{name}` in `sample` is reversed ({low_text} .. {high_text}): write the lower end \
                     first, `{name} = {high_text} .. {low_text}`"
                )
            };
            lower.cx.error_at(item.name.span(), message);
        }
        let slot = if let Some(i) = coords.iter().position(|c| *c == item.name) {
            &mut q_ranges[i]
        } else if let Some(k) = mu.and_then(|mu| mu.iter().position(|c| *c == item.name)) {
            &mut mu_ranges[k]
        } else {
            lower.cx.error_at(
                item.name.span(),
                format!(
                    "`{}` in `sample` is not a coordinate{}: give a range for each coordinate, e.g. `{} = 1.0 .. 10.0`",
                    item.name,
                    if mu.is_some() { " or minimal coordinate" } else { "" },
                    coords.first().map_or("x".to_string(), ToString::to_string),
                ),
            );
            continue;
        };
        if slot.is_some() {
            lower.cx.error_at(
                item.name.span(),
                format!("duplicate range for `{}` in `sample`", item.name),
            );
        }
        *slot = Some((item.low.clone(), item.high.clone()));
    }
    let missing = |ranges: &[Option<(Expr, Expr)>], names: &[Ident]| -> Vec<String> {
        ranges
            .iter()
            .zip(names)
            .filter(|(r, _)| r.is_none())
            .map(|(_, n)| n.to_string())
            .collect()
    };
    let q_missing = missing(&q_ranges, coords);
    if !q_missing.is_empty() {
        lower.cx.error_at(
            section.keyword.span(),
            format!(
                "`sample` needs a range for every coordinate; missing: {} (write e.g. `{} = -10.0 .. 10.0`)",
                q_missing.join(", "),
                q_missing[0]
            ),
        );
        return None;
    }
    let mu_ranges = match mu {
        Some(mu) => {
            let mu_missing = missing(&mu_ranges, mu);
            if !mu_missing.is_empty() {
                lower.cx.error_at(
                    section.keyword.span(),
                    format!(
                        "`sample` needs a range for every minimal coordinate too, so that the self-test checks \
                         the minimal map; missing: {} (write e.g. `{} = 0.0 .. 1.0`)",
                        mu_missing.join(", "),
                        mu_missing[0]
                    ),
                );
                return None;
            }
            Some(mu_ranges.into_iter().flatten().collect())
        }
        None => None,
    };
    Some(SelfTest {
        q: q_ranges.into_iter().flatten().collect(),
        mu: mu_ranges,
    })
}
