//! Double-double numbers: an unevaluated sum `hi + lo` of two `f64`, about
//! 106 bits (32 digits) of precision, for the few quantities that must be
//! known beyond double precision.
//!
//! A scheme for eqs. (22) takes the accelerations from second divided
//! differences of the coordinates, `a ~ (p_{n+1} - 2 p_n + p_{n-1}) / dt^2`.
//! Coordinates rounded to double precision (`~1e-16 |p|` each) carry noise
//! of random sign from step to step, which those differences amplify like
//! `1/dt^2`: the inputs of a finer step are less accurate. Held as
//! double-doubles and solved from constraints evaluated in double-double
//! arithmetic, the coordinates' noise is `~1e-32 |p|`, and the differences
//! stay exact far below any step a run takes.
//!
//! [`DoubleDouble`] implements [`DualNum`], so every generated model
//! function (generic in [`Scalar`](crate::model::Scalar)) evaluates in it.
//! The arithmetic is that of Dekker (1971) and of Hida, Li and Bailey's
//! QD library: error-free sums and products (the product by `f64::mul_add`).
//! `+ - * /`, `sqrt`, `sin`, `cos`, `tan`, `exp`, `ln`, `atan2`, `powi` and
//! `powf` (what `crane_model!` declarations use) are accurate to a few
//! units of `2^-104`; the other functions of [`DualNum`] are built from
//! those by identities and lose accuracy where the identity cancels
//! (`sinh` near 0, `acosh` near 1).
//!
//! ```
//! use crane_runtime::double_double::DoubleDouble;
//! let third = DoubleDouble::from(1.0) / DoubleDouble::from(3.0);
//! // 3 x (1/3) - 1 is 0 to about 1e-32, where f64 gives 0 only by luck
//! let residual = third * 3.0 - 1.0;
//! assert!(residual.hi.abs() < 1e-31);
//! // sin^2 + cos^2 = 1 to about 1e-32
//! let x = DoubleDouble::from(0.7) + DoubleDouble::new(0.0, 1e-20);
//! let one = x.sin() * x.sin() + x.cos() * x.cos();
//! assert!((one - 1.0).hi.abs() < 1e-31);
//! # use num_dual::DualNum;
//! ```

use std::cmp::Ordering;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign};

use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};

/// `hi + lo` with `|lo| <= ulp(hi) / 2`: a number to about 106 bits.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DoubleDouble {
    /// The leading part: the number rounded to `f64`.
    pub hi: f64,
    /// The trailing part, below half an ulp of `hi`.
    pub lo: f64,
}

/// `a + b = s + e` exactly (Knuth's two-sum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a + b = s + e` exactly, for `|a| >= |b|` (Dekker's fast two-sum).
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `a b = p + e` exactly (by the fused multiply-add; measured, Dekker's
/// splitting instead of a call to it made eqs. (22) 5 % slower).
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `pi/2`, `ln 2` and `1/n!` to double-double precision (from their
/// decimal expansions to 34 digits).
const HALF_PI: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::FRAC_PI_2,
    lo: 6.123_233_995_736_766e-17,
};
const LN_2: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::LN_2,
    lo: 2.319_046_813_846_299_6e-17,
};

impl DoubleDouble {
    /// `hi + lo`, normalised so that `|lo| <= ulp(hi) / 2`.
    pub fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        Self { hi, lo }
    }

    /// The exact sum of two `f64`.
    pub fn sum(a: f64, b: f64) -> Self {
        let (hi, lo) = two_sum(a, b);
        Self { hi, lo }
    }

    /// The exact product of two `f64`.
    pub fn product(a: f64, b: f64) -> Self {
        let (hi, lo) = two_prod(a, b);
        Self { hi, lo }
    }

    /// `t0 + n dt` to double-double precision: the time of step `n` of a
    /// run, free of the rounding of `t0 + n dt` in `f64`.
    pub fn step_time(t0: f64, n: u64, dt: f64) -> Self {
        Self::product(n as f64, dt) + t0
    }

    /// The number rounded to `f64`.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// Whether both parts are finite.
    pub fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    fn nan() -> Self {
        Self {
            hi: f64::NAN,
            lo: f64::NAN,
        }
    }

    /// `self * b` for an `f64` `b`.
    #[inline]
    fn mul_f64(self, b: f64) -> Self {
        let (p, e) = two_prod(self.hi, b);
        let (hi, lo) = quick_two_sum(p, e + self.lo * b);
        Self { hi, lo }
    }

    /// `self / b` for an `f64` `b`.
    #[inline]
    fn div_f64(self, b: f64) -> Self {
        let q1 = self.hi / b;
        // the remainder self - q1 b, exactly in its leading parts
        let (p, e) = two_prod(q1, b);
        let (s, f) = two_sum(self.hi, -p);
        let q2 = (s + (f - e + self.lo)) / b;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self { hi, lo }
    }

    /// `sin` and `cos` of a number in `[-pi/4, pi/4]` by their Taylor
    /// series in Horner form, `sin r / r = 1 - r^2/(2 3) (1 - r^2/(4 5) (...))`,
    /// `cos r = 1 - r^2/(1 2) (1 - r^2/(3 4) (...))`: the terms from
    /// `r^20` on (below `1e-33` of the sum at `|r| = pi/4`) in `f64`, the
    /// others in double-double.
    fn sin_cos_reduced(r: Self) -> (Self, Self) {
        let r2 = r * r;
        let (mut s_tail, mut c_tail) = (1.0_f64, 1.0_f64);
        for k in (10..=13).rev() {
            s_tail = 1.0 - r2.hi * s_tail / ((2 * k) * (2 * k + 1)) as f64;
            c_tail = 1.0 - r2.hi * c_tail / ((2 * k - 1) * (2 * k)) as f64;
        }
        let (mut s, mut c) = (Self::from(s_tail), Self::from(c_tail));
        for k in (1..=9).rev() {
            s = -(r2 * s).div_f64(((2 * k) * (2 * k + 1)) as f64) + 1.0;
            c = -(r2 * c).div_f64(((2 * k - 1) * (2 * k)) as f64) + 1.0;
        }
        (r * s, c)
    }

    /// `exp(r) - 1` for `|r|` at most `ln(2)/2`: `exp(r/2^8) - 1` by its
    /// Taylor series, then `(1 + m)^2 - 1 = m (2 + m)` eight times.
    fn exp_m1_reduced(r: Self) -> Self {
        let x = r.div_f64(256.0);
        // exp(x) - 1 = x (1 + x/2 (1 + x/3 (...))), |x| < 1.4e-3: 12 terms
        let mut e = Self::from(1.0);
        for k in (2..=12).rev() {
            e = (x * e).div_f64(k as f64) + 1.0;
        }
        let mut m = x * e;
        for _ in 0..8 {
            m = m * (m + 2.0);
        }
        m
    }

    /// `sin` and `cos`, reduced by a multiple `k` of `pi/2`, then by the
    /// Taylor series.
    fn sin_cos_uncached(self) -> (Self, Self) {
        let k = (self.hi / HALF_PI.hi).round();
        let r = self - HALF_PI * k;
        let (s, c) = Self::sin_cos_reduced(r);
        match (k as i64).rem_euclid(4) {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }
}

/// The last [`MEMO_SIZE`] arguments of `sin_cos` and their values, a ring.
/// A generated model function evaluates `sin` and `cos` of the same
/// angles (a parameter's, a coordinate's) in every function and every
/// iteration of a step; their series costs about as much as the rest of
/// the function.
struct SinCosMemo {
    keys: [(u64, u64); MEMO_SIZE],
    values: [(DoubleDouble, DoubleDouble); MEMO_SIZE],
    next: usize,
}

/// How many arguments [`SinCosMemo`] keeps.
const MEMO_SIZE: usize = 8;

impl SinCosMemo {
    fn find(&self, key: (u64, u64)) -> Option<(DoubleDouble, DoubleDouble)> {
        self.keys.iter().position(|&k| k == key).map(|i| self.values[i])
    }

    fn keep(&mut self, key: (u64, u64), value: (DoubleDouble, DoubleDouble)) {
        self.keys[self.next] = key;
        self.values[self.next] = value;
        self.next = (self.next + 1) % MEMO_SIZE;
    }
}

thread_local! {
    /// The memo of [`DualNum::sin_cos`] on [`DoubleDouble`] (a NaN key,
    /// which no finite argument has, marks an empty entry).
    static SIN_COS_MEMO: std::cell::RefCell<SinCosMemo> = const {
        std::cell::RefCell::new(SinCosMemo {
            keys: [(u64::MAX, u64::MAX); MEMO_SIZE],
            values: [(DoubleDouble { hi: 0.0, lo: 0.0 }, DoubleDouble { hi: 0.0, lo: 0.0 }); MEMO_SIZE],
            next: 0,
        })
    };
}

impl From<f64> for DoubleDouble {
    fn from(hi: f64) -> Self {
        Self { hi, lo: 0.0 }
    }
}

impl fmt::Display for DoubleDouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.lo == 0.0 {
            write!(f, "{}", self.hi)
        } else {
            write!(f, "{} + {:e}", self.hi, self.lo)
        }
    }
}

impl PartialOrd for DoubleDouble {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        match self.hi.partial_cmp(&other.hi)? {
            Ordering::Equal => self.lo.partial_cmp(&other.lo),
            order => Some(order),
        }
    }
}

impl PartialEq<f64> for DoubleDouble {
    fn eq(&self, other: &f64) -> bool {
        *self == Self::from(*other)
    }
}

impl PartialOrd<f64> for DoubleDouble {
    fn partial_cmp(&self, other: &f64) -> Option<Ordering> {
        self.partial_cmp(&Self::from(*other))
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    /// The accurate sum (QD's `ieee_add`): both parts two-summed.
    fn add(self, b: Self) -> Self {
        let (s, e) = two_sum(self.hi, b.hi);
        if !s.is_finite() {
            // an infinity or NaN as f64 has it (the error terms would be NaN)
            return Self::from(s);
        }
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        Self { hi, lo }
    }
}

impl Add<f64> for DoubleDouble {
    type Output = Self;
    fn add(self, b: f64) -> Self {
        let (s, e) = two_sum(self.hi, b);
        if !s.is_finite() {
            return Self::from(s);
        }
        let (hi, lo) = quick_two_sum(s, e + self.lo);
        Self { hi, lo }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Sub<f64> for DoubleDouble {
    type Output = Self;
    fn sub(self, b: f64) -> Self {
        self + (-b)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    fn mul(self, b: Self) -> Self {
        let (p, e) = two_prod(self.hi, b.hi);
        let (hi, lo) = quick_two_sum(p, e + (self.hi * b.lo + self.lo * b.hi));
        Self { hi, lo }
    }
}

impl Mul<f64> for DoubleDouble {
    type Output = Self;
    fn mul(self, b: f64) -> Self {
        self.mul_f64(b)
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    /// Three quotient digits (QD's accurate division); by zero or an
    /// infinity as `f64` divides.
    fn div(self, b: Self) -> Self {
        let q1 = self.hi / b.hi;
        if !q1.is_finite() || !b.hi.is_finite() {
            return Self::from(q1);
        }
        let r = self - b * q1;
        let q2 = r.hi / b.hi;
        let r = r - b * q2;
        let q3 = r.hi / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        Self { hi, lo } + q3
    }
}

impl Div<f64> for DoubleDouble {
    type Output = Self;
    fn div(self, b: f64) -> Self {
        self.div_f64(b)
    }
}

impl Rem for DoubleDouble {
    type Output = Self;
    /// `self - trunc(self / b) b`, as `f64`'s `%`: the remainder has the
    /// sign of `self` (a quotient just below a whole number, whose `hi` is
    /// that number, takes the one below).
    fn rem(self, b: Self) -> Self {
        let q = self / b;
        let mut whole = if q.hi.fract() == 0.0 {
            Self::new(q.hi, q.lo.trunc())
        } else {
            Self::from(q.hi.trunc())
        };
        let mut rest = self - b * whole;
        if rest.hi != 0.0 && (rest.hi < 0.0) != (self.hi < 0.0) {
            whole -= q.hi.signum();
            rest = self - b * whole;
        }
        rest
    }
}

impl Rem<f64> for DoubleDouble {
    type Output = Self;
    fn rem(self, b: f64) -> Self {
        self % Self::from(b)
    }
}

/// `&a op b`, `a op= b` and `a op= f64` from `a op b`.
macro_rules! forward_ops {
    ($($op:ident $method:ident $assign:ident $assign_method:ident),*) => {$(
        impl<'a> $op<&'a DoubleDouble> for DoubleDouble {
            type Output = DoubleDouble;
            fn $method(self, b: &'a DoubleDouble) -> DoubleDouble {
                $op::$method(self, *b)
            }
        }
        impl $assign for DoubleDouble {
            fn $assign_method(&mut self, b: DoubleDouble) {
                *self = $op::$method(*self, b);
            }
        }
        impl $assign<f64> for DoubleDouble {
            fn $assign_method(&mut self, b: f64) {
                *self = $op::$method(*self, b);
            }
        }
        impl<'a> $assign<&'a DoubleDouble> for DoubleDouble {
            fn $assign_method(&mut self, b: &'a DoubleDouble) {
                *self = $op::$method(*self, *b);
            }
        }
    )*};
}

forward_ops!(
    Add add AddAssign add_assign,
    Sub sub SubAssign sub_assign,
    Mul mul MulAssign mul_assign,
    Div div DivAssign div_assign,
    Rem rem RemAssign rem_assign
);

impl Zero for DoubleDouble {
    fn zero() -> Self {
        Self::from(0.0)
    }
    fn is_zero(&self) -> bool {
        self.hi == 0.0
    }
}

impl One for DoubleDouble {
    fn one() -> Self {
        Self::from(1.0)
    }
}

impl Num for DoubleDouble {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    /// Through `f64`: a string gives at most double precision.
    fn from_str_radix(s: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(s, radix).map(Self::from)
    }
}

impl Signed for DoubleDouble {
    fn abs(&self) -> Self {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -*self
        } else {
            *self
        }
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if *self <= *other { Self::zero() } else { *self - *other }
    }
    fn signum(&self) -> Self {
        Self::from(self.hi.signum())
    }
    fn is_positive(&self) -> bool {
        self.hi > 0.0
    }
    fn is_negative(&self) -> bool {
        self.hi < 0.0
    }
}

impl Inv for DoubleDouble {
    type Output = Self;
    fn inv(self) -> Self {
        self.recip()
    }
}

impl Sum for DoubleDouble {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |a, b| a + b)
    }
}

impl Product for DoubleDouble {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::one(), |a, b| a * b)
    }
}

impl FromPrimitive for DoubleDouble {
    fn from_i64(n: i64) -> Option<Self> {
        // exact: the high 53 bits and the rest
        let hi = n as f64;
        Some(Self::new(hi, (i128::from(n) - hi as i128) as f64))
    }
    fn from_u64(n: u64) -> Option<Self> {
        let hi = n as f64;
        Some(Self::new(hi, (i128::from(n) - hi as i128) as f64))
    }
    fn from_f64(x: f64) -> Option<Self> {
        Some(Self::from(x))
    }
}

impl DualStruct for DoubleDouble {
    type Real = f64;
    type Inner = DoubleDouble;
    fn re(&self) -> f64 {
        self.hi
    }
    fn from_inner(inner: &Self::Inner) -> Self {
        *inner
    }
}

impl Mappable<DoubleDouble> for DoubleDouble {
    type Output<O> = O;
    fn map_dual<M: FnOnce(DoubleDouble) -> O, O>(self, f: M) -> O {
        f(self)
    }
}

impl DualNum for DoubleDouble {
    type Primitive = f64;
    const NDERIV: usize = 0;
    type InnerDual = DoubleDouble;

    fn from_re(re: DoubleDouble) -> Self {
        re
    }

    fn scale(self, factor: &DoubleDouble) -> Self {
        self * *factor
    }

    fn recip(&self) -> Self {
        Self::one() / *self
    }

    /// By repeated squaring: exact to a few ulps of double-double.
    fn powi(&self, n: i32) -> Self {
        match n {
            0 => return Self::one(),
            1 => return *self,
            2 => return *self * *self,
            3 => return *self * *self * *self,
            -1 => return self.recip(),
            _ => {}
        }
        let mut base = *self;
        let mut result = Self::one();
        let mut k = n.unsigned_abs();
        while k > 0 {
            if k & 1 == 1 {
                result *= base;
            }
            base = base * base;
            k >>= 1;
        }
        if n < 0 { result.recip() } else { result }
    }

    /// `exp(n ln x)` for `x > 0`; `f64`'s special cases otherwise.
    fn powf(&self, n: f64) -> Self {
        if n == 0.0 {
            return Self::one();
        }
        if self.hi > 0.0 {
            (self.ln() * n).exp()
        } else {
            Self::from(self.hi.powf(n))
        }
    }

    /// One Newton step from the `f64` root: `s + (x - s^2) / (2 s)`.
    fn sqrt(&self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Self::from(self.hi.sqrt());
        }
        let s = self.hi.sqrt();
        let correction = (*self - Self::product(s, s)).hi / (2.0 * s);
        Self::sum(s, correction)
    }

    /// One Newton step from the `f64` root of `y^3 = x`.
    fn cbrt(&self) -> Self {
        let y = self.hi.cbrt();
        if y == 0.0 || !y.is_finite() {
            return Self::from(y);
        }
        let y = Self::from(y);
        y - (y * y * y - *self) / (y * y * 3.0)
    }

    /// `2^k exp(r)`, `|r| <= ln(2)/2`.
    fn exp(&self) -> Self {
        if self.hi > 709.78 {
            return Self::from(f64::INFINITY);
        }
        if self.hi < -745.2 {
            return Self::zero();
        }
        let k = (self.hi / LN_2.hi).round();
        let r = *self - LN_2 * k;
        let e = Self::exp_m1_reduced(r) + 1.0;
        // 2^k in two factors: 2^1024 alone overflows where the product does
        // not (x up to 709.78), 2^-1075 alone underflows
        let (k1, k2) = ((k as i32) / 2, (k as i32) - (k as i32) / 2);
        let (s1, s2) = (2f64.powi(k1), 2f64.powi(k2));
        Self {
            hi: e.hi * s1 * s2,
            lo: e.lo * s1 * s2,
        }
    }

    fn exp2(&self) -> Self {
        (*self * LN_2).exp()
    }

    fn exp_m1(&self) -> Self {
        if self.hi.abs() < 0.3 {
            Self::exp_m1_reduced(*self)
        } else {
            self.exp() - 1.0
        }
    }

    /// One Newton step from the `f64` logarithm: `y + x exp(-y) - 1`.
    fn ln(&self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Self::from(self.hi.ln());
        }
        let y = Self::from(self.hi.ln());
        y + *self * (-y).exp() - 1.0
    }

    fn log(&self, base: f64) -> Self {
        self.ln() / Self::from(base).ln()
    }

    fn log2(&self) -> Self {
        self.ln() / LN_2
    }

    fn log10(&self) -> Self {
        self.ln() / Self::from(10.0).ln()
    }

    fn ln_1p(&self) -> Self {
        (*self + 1.0).ln()
    }

    fn sin(&self) -> Self {
        self.sin_cos().0
    }

    fn cos(&self) -> Self {
        self.sin_cos().1
    }

    fn tan(&self) -> Self {
        let (s, c) = self.sin_cos();
        s / c
    }

    /// Reduced by a multiple `k` of `pi/2` (in double-double, whose `pi/2`
    /// is off by about 1e-33: the reduction's error grows like 1e-33 `|k|`,
    /// negligible for the angles of a crane), then by the Taylor series;
    /// the last few arguments' values are kept per thread.
    fn sin_cos(&self) -> (Self, Self) {
        if !self.is_finite() {
            return (Self::nan(), Self::nan());
        }
        let key = (self.hi.to_bits(), self.lo.to_bits());
        if let Some(found) = SIN_COS_MEMO.with_borrow(|memo| memo.find(key)) {
            return found;
        }
        let value = self.sin_cos_uncached();
        SIN_COS_MEMO.with_borrow_mut(|memo| memo.keep(key, value));
        value
    }

    fn asin(&self) -> Self {
        self.atan2((Self::one() - *self * *self).sqrt())
    }

    fn acos(&self) -> Self {
        (Self::one() - *self * *self).sqrt().atan2(*self)
    }

    fn atan(&self) -> Self {
        self.atan2(Self::one())
    }

    /// One Newton step from the `f64` angle `theta`:
    /// `theta + (y cos theta - x sin theta) / (x cos theta + y sin theta)`.
    fn atan2(&self, x: Self) -> Self {
        let y = *self;
        let theta = y.hi.atan2(x.hi);
        if !theta.is_finite() || (y.hi == 0.0 && x.hi == 0.0) {
            return Self::from(theta);
        }
        let theta = Self::from(theta);
        let (s, c) = theta.sin_cos();
        theta + (y * c - x * s) / (x * c + y * s)
    }

    fn sinh(&self) -> Self {
        let e = self.exp();
        (e - e.recip()) * 0.5
    }

    fn cosh(&self) -> Self {
        let e = self.exp();
        (e + e.recip()) * 0.5
    }

    fn tanh(&self) -> Self {
        let e2 = (*self * 2.0).exp();
        (e2 - 1.0) / (e2 + 1.0)
    }

    fn asinh(&self) -> Self {
        (*self + (*self * *self + 1.0).sqrt()).ln()
    }

    fn acosh(&self) -> Self {
        (*self + (*self * *self - 1.0).sqrt()).ln()
    }

    fn atanh(&self) -> Self {
        ((Self::one() + *self) / (Self::one() - *self)).ln() * 0.5
    }

    fn sph_j0(&self) -> Self {
        if self.hi.abs() < f64::EPSILON {
            Self::one() - *self * *self / 6.0
        } else {
            self.sin() / *self
        }
    }

    fn sph_j1(&self) -> Self {
        if self.hi.abs() < f64::EPSILON {
            *self / 3.0
        } else {
            let (s, c) = self.sin_cos();
            let rec = self.recip();
            (s * rec - c) * rec
        }
    }

    fn sph_j2(&self) -> Self {
        if self.hi.abs() < f64::EPSILON {
            *self * *self / 15.0
        } else {
            let (s, c) = self.sin_cos();
            let s2 = *self * *self;
            ((-s2 + 3.0) * s - *self * c * 3.0) / (*self * s2)
        }
    }

    fn mul_add(&self, a: Self, b: Self) -> Self {
        *self * a + b
    }

    fn powd(&self, n: Self) -> Self {
        (self.ln() * n).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `2^-104`: one ulp of a double-double near 1.
    const ULP: f64 = 4.930_380_657_631_324e-32;

    fn close(a: DoubleDouble, b: DoubleDouble, ulps: f64) -> bool {
        let scale = a.hi.abs().max(b.hi.abs()).max(f64::MIN_POSITIVE);
        (a - b).hi.abs() <= ulps * ULP * scale
    }

    /// Arithmetic against identities that hold exactly in the reals:
    /// `(a b) / b = a`, `(a + b) - b = a`, `sqrt(x)^2 = x`, each to a few
    /// ulps of double-double (where `f64` is off by up to 1e-16).
    #[test]
    fn arithmetic_holds_its_identities_to_double_double_precision() {
        let values = [0.1, 1.0 / 3.0, 2.0_f64.sqrt(), 12.5, 1e-8, 3e7, -7.25];
        for &x in &values {
            for &y in &values {
                let a = DoubleDouble::new(x, x * 1e-17);
                let b = DoubleDouble::new(y, -y * 3e-18);
                assert!(close((a * b) / b, a, 8.0), "{x} {y}");
                assert!(close((a + b) - b, a, 8.0 * (b.hi / a.hi).abs().max(1.0)), "{x} {y}");
                assert!(close((a / b) * b, a, 8.0), "{x} {y}");
            }
            let a = DoubleDouble::new(x.abs(), x.abs() * 1e-17);
            let s = a.sqrt();
            assert!(close(s * s, a, 8.0), "sqrt {x}");
        }
    }

    /// `sin^2 + cos^2 = 1`, `sin(2x) = 2 sin x cos x` and `exp(ln x) = x`,
    /// `tan(atan2(y, x)) = y / x`, to a few ulps over a range of
    /// arguments (every quadrant of the reduction).
    #[test]
    fn functions_hold_their_identities_to_double_double_precision() {
        for i in -40..=40 {
            let x = DoubleDouble::new(0.37 * f64::from(i) + 0.011, 1.3e-18 * f64::from(i));
            let (s, c) = x.sin_cos();
            assert!(close(s * s + c * c, DoubleDouble::one(), 16.0), "x = {x}");
            let (s2, _) = (x * 2.0).sin_cos();
            assert!((s2 - s * c * 2.0).hi.abs() <= 64.0 * ULP, "x = {x}");
            let e = DoubleDouble::from(0.5 + 0.1 * f64::from(i + 41));
            assert!(close(e.ln().exp(), e, 32.0), "e = {e}");
            let (y, xx) = (s, c);
            let angle = y.atan2(xx);
            let (sa, ca) = angle.sin_cos();
            assert!(close(sa / ca, y / xx, 64.0), "atan2 at {x}");
        }
    }

    /// Against values known to 32 digits (from tables): `sin(1)`,
    /// `cos(1)`, `e`, `ln(10)`, `sqrt(2)`, split into the nearest `f64`
    /// and the rest.
    #[test]
    fn functions_match_tabulated_values() {
        let one = DoubleDouble::one();
        let cases = [
            ("sin 1", one.sin(), 0.841_470_984_807_896_5, 1.776_845_092_935_536e-18),
            ("cos 1", one.cos(), 0.540_302_305_868_139_8, -4.760_954_612_604_417e-17),
            ("e", one.exp(), std::f64::consts::E, 1.445_646_891_729_250_2e-16),
            (
                "ln 10",
                DoubleDouble::from(10.0).ln(),
                std::f64::consts::LN_10,
                -2.170_756_223_382_249_4e-16,
            ),
            (
                "sqrt 2",
                DoubleDouble::from(2.0).sqrt(),
                std::f64::consts::SQRT_2,
                -9.667_293_313_452_913e-17,
            ),
        ];
        for (name, value, hi, lo) in cases {
            assert_eq!(value.hi, hi, "{name}");
            assert!(
                (value.lo - lo).abs() <= 4.0 * ULP * hi,
                "{name}: lo {:e} against {lo:e}",
                value.lo
            );
        }
    }

    /// The edges, as `f64` has them: `exp` up to its overflow and down to
    /// its underflow, `sqrt` and sums of infinities, division by zero, and
    /// the remainder of a quotient just below a whole number.
    #[test]
    fn edges_are_those_of_f64() {
        for x in [709.6, 709.78, -740.0, -20.5] {
            let e = DoubleDouble::from(x).exp();
            assert!(
                e.is_finite() && (e.hi - x.exp()).abs() <= 4e-16 * x.exp(),
                "exp({x}) = {e}"
            );
        }
        assert_eq!(DoubleDouble::from(f64::INFINITY).sqrt().hi, f64::INFINITY);
        assert_eq!((DoubleDouble::from(f64::INFINITY) + 1.0).hi, f64::INFINITY);
        assert_eq!((DoubleDouble::from(1.0) / DoubleDouble::from(0.0)).hi, f64::INFINITY);
        // (3 - 3e-17) % 1 = 1 - 3e-17, whose leading part rounds to 1
        let rest = DoubleDouble::new(3.0, -3e-17) % 1.0;
        assert!(rest > 0.999 && rest < 1.0 && (rest - 1.0).hi == -3e-17, "{rest}");
        let rest = DoubleDouble::new(-3.0, 3e-17) % 1.0;
        assert!(rest < -0.999 && rest > -1.0 && (rest + 1.0).hi == 3e-17, "{rest}");
        assert_eq!((DoubleDouble::from(7.5) % 2.0).hi, 1.5);
    }

    /// The exact time of a step: `t0 + n dt` with what `f64` rounds away.
    #[test]
    fn a_step_time_keeps_what_f64_rounds_away() {
        // 1 + 3 x 0.1000000000000000055511151231257827 (the f64 0.1)
        // = 1.3 (the f64 1.3000000000000000444) - 2.7755575615628914e-17
        let t = DoubleDouble::step_time(1.0, 3, 0.1);
        assert_eq!(t.hi, 1.3);
        assert!((t.lo + 2.775_557_561_562_891_4e-17).abs() < 1e-32, "{:e}", t.lo);
    }
}
