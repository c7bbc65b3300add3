//! Orthonormal frames around a normal.

use glam::Vec3;

/// Two unit tangents `(t, b)` such that `(t, b, n)` is a right-handed orthonormal
/// basis, without branches (Duff, Burgess, Christensen, Hery, Kensler, Liani and
/// Villemin 2017, "Building an Orthonormal Basis, Revisited", Listing 3).
///
/// `n` must be a unit vector. With `s = sign(n.z)` (+1 for +0) and
/// `a = -1 / (s + n.z)`, `b = n.x n.y a`:
/// `t = (1 + s n.x² a, s b, -s n.x)`, `b = (b, s + n.y² a, -n.y)`.
/// The singularity of Frisvad's method at `n.z = -1` is moved to `n.z = 0` where `s`
/// flips, and there `s + n.z = ±1` keeps the division safe.
#[inline(always)]
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bitangent = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bitangent)
}

/// A local shading frame: z is the normal. Converts world directions to local ones
/// and back.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent (local x).
    pub tangent: Vec3,
    /// Second tangent (local y).
    pub bitangent: Vec3,
    /// The normal (local z).
    pub normal: Vec3,
}

impl Frame {
    /// The frame around a unit normal, from [`orthonormal_basis`]. Returns `None` for a
    /// normal that is not finite or is far from unit length (|n|² outside 1 ± 1e-3).
    pub fn from_normal(normal: Vec3) -> Option<Frame> {
        let length_squared = normal.length_squared();
        if !normal.is_finite() || (length_squared - 1.0).abs() > 1e-3 {
            return None;
        }
        let (tangent, bitangent) = orthonormal_basis(normal);
        Some(Frame {
            tangent,
            bitangent,
            normal,
        })
    }

    /// Expresses a world-space vector in this frame.
    #[inline(always)]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(
            v.dot(self.tangent),
            v.dot(self.bitangent),
            v.dot(self.normal),
        )
    }

    /// Expresses a local vector in world space.
    #[inline(always)]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.tangent * v.x + self.bitangent * v.y + self.normal * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Rng;

    #[test]
    fn basis_is_orthonormal_and_right_handed_to_f64_accuracy() {
        let mut rng = Rng::new(21);
        let mut worst = 0.0f64;
        let mut normals: [Vec3; 6] = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::Y,
            Vec3::new(0.0, 0.0, -0.0),
            Vec3::new(1e-8, 0.0, -1.0).normalize(),
        ];
        normals[4] = Vec3::new(0.6, 0.8, -0.0);
        let mut check = |n: Vec3| {
            let (t, b) = orthonormal_basis(n);
            let [t, b, n] = [t, b, n].map(|v| [v.x as f64, v.y as f64, v.z as f64]);
            let dot = |a: [f64; 3], c: [f64; 3]| a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
            let cross = [
                t[1] * b[2] - t[2] * b[1],
                t[2] * b[0] - t[0] * b[2],
                t[0] * b[1] - t[1] * b[0],
            ];
            for e in [
                dot(t, t) - 1.0,
                dot(b, b) - 1.0,
                dot(t, b),
                dot(t, n),
                dot(b, n),
                dot(cross, n) - 1.0,
            ] {
                worst = worst.max(e.abs());
            }
        };
        for n in normals {
            check(n);
        }
        for _ in 0..100_000 {
            check(rng.unit_vector_f32());
        }
        assert!(worst < 1e-6, "worst deviation from orthonormality {worst}");
    }

    #[test]
    fn frame_round_trips_and_rejects_bad_normals() {
        let f = Frame::from_normal(Vec3::new(0.0, 0.6, 0.8)).unwrap();
        let v = Vec3::new(0.3, -0.2, 0.9);
        assert!((f.to_world(f.to_local(v)) - v).length() < 1e-6);
        assert!((f.to_local(f.normal) - Vec3::Z).length() < 1e-6);
        assert!(Frame::from_normal(Vec3::new(f32::NAN, 0.0, 1.0)).is_none());
        assert!(Frame::from_normal(Vec3::new(0.0, 0.0, 2.0)).is_none());
        assert!(Frame::from_normal(Vec3::ZERO).is_none());
    }
}
