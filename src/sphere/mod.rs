//! Sphere lights (Dupuy, Heitz, Belcour 2017): spherical caps, the pivot
//! transformation, spherical pivot transformed distributions, and the pivot phase function.

pub mod phase;
