//! Which technique carried each part of a sample's radiance: the viewer's technique map (where in
//! the image light sampling, and where BSDF sampling, carries the estimate).
//!
//! The path tracer adds every contribution to the sample under one [`Technique`], with the
//! weight it actually applied (the MIS or mixture weight, or 1 where a technique is alone), so
//! the parts of a sample add up to its radiance (up to f32 rounding of the order of the sums) and
//! the parts' means add up to the image. The split is recorded only when asked for
//! ([`crate::engine::Progressive::enable_technique_map`]); the radiance is the same bit for bit
//! either way. CPU only: the GPU kernels do not record it.

use glam::Vec3;

/// What produced a contribution to a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Technique {
    /// Emission the camera ray itself hit (or the environment it escaped to): no estimator of
    /// direct light is involved.
    Camera,
    /// Next-event estimation: a light sample and its shadow ray, at any vertex.
    Light,
    /// Emission found by a BSDF-sampled ray (any bounce, delta lobes included).
    Bsdf,
    /// `mis-optimal`'s control variate (α and the −α·r terms), which belongs to neither.
    ControlVariate,
}

impl Technique {
    /// Every technique, in the order of [`TechniqueSplit::parts`].
    pub const ALL: [Technique; 4] = [
        Technique::Camera,
        Technique::Light,
        Technique::Bsdf,
        Technique::ControlVariate,
    ];

    /// Index into [`TechniqueSplit::parts`] and [`TechniqueSums::sum`].
    pub const fn index(self) -> usize {
        match self {
            Technique::Camera => 0,
            Technique::Light => 1,
            Technique::Bsdf => 2,
            Technique::ControlVariate => 3,
        }
    }
}

/// One sample's radiance, split by the technique that contributed it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TechniqueSplit {
    /// Contributions in [`Technique::ALL`] order.
    pub parts: [Vec3; 4],
}

impl TechniqueSplit {
    /// Adds `v` to the part of `technique`.
    #[inline]
    pub fn add(&mut self, technique: Technique, v: Vec3) {
        self.parts[technique.index()] += v;
    }

    /// The part of `technique`.
    pub fn part(&self, technique: Technique) -> Vec3 {
        self.parts[technique.index()]
    }
}

/// A pixel's sums of [`TechniqueSplit`]s over its samples, in f64 like the film's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TechniqueSums {
    /// Σ of each part, per channel, in [`Technique::ALL`] order.
    pub sum: [[f64; 3]; 4],
}

impl TechniqueSums {
    /// Adds one sample's split.
    #[inline]
    pub fn add(&mut self, split: &TechniqueSplit) {
        for (s, p) in self.sum.iter_mut().zip(split.parts) {
            s[0] += p.x as f64;
            s[1] += p.y as f64;
            s[2] += p.z as f64;
        }
    }

    /// The mean of each part over `spp` samples (zeros for none), in [`Technique::ALL`] order.
    pub fn means(&self, spp: u32) -> [Vec3; 4] {
        let k = if spp == 0 { 0.0 } else { 1.0 / spp as f64 };
        self.sum
            .map(|s| Vec3::new((s[0] * k) as f32, (s[1] * k) as f32, (s[2] * k) as f32))
    }
}

/// The share of a pixel's direct light that light samples carried: `light / (light + bsdf)` of
/// the parts' luminances (Rec. 709), in [0, 1]; `None` where neither carried any. The camera's
/// own view of emitters is not direct light of a surface and is left out, and so is
/// `mis-optimal`'s control variate, whose terms sum to about zero.
pub fn light_share(light: Vec3, bsdf: Vec3) -> Option<f32> {
    let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722)).max(0.0);
    let (l, b) = (lum(light), lum(bsdf));
    (l + b > 0.0 && (l + b).is_finite()).then(|| l / (l + b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_follow_all_and_sums_average() {
        for (i, t) in Technique::ALL.iter().enumerate() {
            assert_eq!(t.index(), i);
        }
        let mut split = TechniqueSplit::default();
        split.add(Technique::Light, Vec3::splat(3.0));
        split.add(Technique::Bsdf, Vec3::new(1.0, 2.0, 3.0));
        split.add(Technique::Light, Vec3::splat(1.0));
        assert_eq!(split.part(Technique::Light), Vec3::splat(4.0));
        let mut sums = TechniqueSums::default();
        sums.add(&split);
        sums.add(&TechniqueSplit::default());
        let m = sums.means(2);
        assert_eq!(m[Technique::Light.index()], Vec3::splat(2.0));
        assert_eq!(m[Technique::Bsdf.index()], Vec3::new(0.5, 1.0, 1.5));
        assert_eq!(m[Technique::Camera.index()], Vec3::ZERO);
        assert_eq!(TechniqueSums::default().means(0), [Vec3::ZERO; 4]);
    }

    #[test]
    fn light_share_is_the_luminance_fraction() {
        assert_eq!(light_share(Vec3::ONE, Vec3::ZERO), Some(1.0));
        assert_eq!(light_share(Vec3::ZERO, Vec3::ONE), Some(0.0));
        assert_eq!(light_share(Vec3::splat(3.0), Vec3::ONE), Some(0.75));
        assert_eq!(light_share(Vec3::ZERO, Vec3::ZERO), None);
        assert_eq!(light_share(Vec3::splat(f32::INFINITY), Vec3::ONE), None);
    }
}
