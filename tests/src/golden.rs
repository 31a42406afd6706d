//! Golden-section minimisation for the tests' brute-force oracles (the GEO tour's
//! `geo_tour_fixtures` and `geo_tour_brute`): independent of the planner's own section in
//! `core/src/geo_tour/lambert_phasing.rs`, which is what they check.

/// Minimise `f` on `[lo, hi]` by `iters` golden-section steps; the better of the two interior
/// points left, `(x, f(x))`.
pub fn golden(lo: f64, hi: f64, iters: usize, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..iters {
        if fc <= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    if fc <= fd {
        (c, fc)
    } else {
        (d, fd)
    }
}
