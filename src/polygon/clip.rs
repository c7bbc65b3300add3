//! In-situ clipping of convex polygons to the upper hemisphere (supplement A.1).
use glam::Vec3;

/// Clips the convex polygon `vertices[..count]` to `z >= 0` in place and returns the
/// new vertex count: 0 or 3..=8. STUB.
pub fn clip_to_upper_hemisphere(vertices: &mut [Vec3; 8], count: usize) -> usize {
    let _ = vertices;
    let _ = count;
    0
}
