//! STUB
use crate::Sample;
use glam::Vec3;

/// STUB
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct ArvoPolygon {
    vertices: [Vec3; 8],
    count: u32,
}

impl ArvoPolygon {
    /// STUB
    pub const EMPTY: Self = Self { vertices: [Vec3::ZERO; 8], count: 0 };
    /// STUB
    pub fn new(vertices: &[Vec3]) -> Option<Self> { let _ = vertices; None }
    /// STUB
    pub fn sample(&self, u: [f32; 2]) -> Sample { let _ = (u, self.count, self.vertices); Sample::NONE }
    /// STUB
    pub fn pdf(&self, dir: Vec3) -> f32 { let _ = dir; 0.0 }
    /// STUB
    pub fn solid_angle(&self) -> f32 { 0.0 }
}
