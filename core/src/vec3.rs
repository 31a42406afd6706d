//! Small 3-vector arithmetic shared by the planners (km, km/s or any unit: the functions are
//! unit-free). Plain arrays, written out component by component so that every build evaluates
//! the same operations in the same order (no fused multiply-add, bit-identical host and M7).

/// A 3-vector.
pub type Vec3 = [f64; 3];

/// `a . b`.
pub(crate) fn dot(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
pub(crate) fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `|a|`.
pub(crate) fn norm(a: &Vec3) -> f64 {
    libm::sqrt(dot(a, a))
}

/// `k a`.
pub(crate) fn scale(a: &Vec3, k: f64) -> Vec3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

/// `a + b`.
pub(crate) fn add(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
pub(crate) fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
