//! A root with a rigorous inclusion disk: what the double-double refinement (`refine.rs`) and
//! the multi-precision one (`mp.rs`) both return.

use num_complex::Complex64;

use super::cdd::Cdd;

/// A root with its inclusion radius.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DiskRoot {
    /// Centre of the disk (the reported root is its rounding to doubles).
    pub z: Cdd,
    /// Radius (rigorous upper bound of the distance to the one root inside).
    pub r: f64,
}

impl DiskRoot {
    /// True when the disk lies in the open left (−1) or right (+1) half plane; 0 when it
    /// touches the imaginary axis.
    pub fn side(&self) -> i32 {
        let re = self.z.re.to_f64();
        if re.abs() > self.r * (1.0 + 1e-12) + f64::MIN_POSITIVE {
            if re > 0.0 { 1 } else { -1 }
        } else {
            0
        }
    }

    /// The root as a complex double (real roots have an imaginary part of exactly 0).
    pub fn value(&self) -> Complex64 {
        self.z.to_c64()
    }
}
