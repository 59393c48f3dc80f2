//! The build may use instructions the base x86-64 lacks (`.cargo/config.toml` asks for
//! x86-64-v3); a CPU without them would die on an illegal instruction somewhere in the middle of
//! a render. [`missing_features`] compares what the build was compiled for with what this CPU
//! reports, so `lumis` can say so in one line at start instead.

/// The target features this build was compiled with (among those x86-64-v3 adds) that this CPU
/// does not report. Empty on every other architecture and on a build for the base x86-64.
pub fn missing_features() -> Vec<&'static str> {
    #[allow(unused_mut)]
    let mut missing = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! check {
            ($($feature:tt),*) => {$(
                if cfg!(target_feature = $feature) && !std::arch::is_x86_feature_detected!($feature) {
                    missing.push($feature);
                }
            )*};
        }
        check!(
            "avx", "avx2", "fma", "bmi1", "bmi2", "lzcnt", "movbe", "f16c", "popcnt", "sse4.2"
        );
    }
    missing
}

/// The one-line error for [`missing_features`], or `None` when nothing is missing.
pub fn check() -> Option<String> {
    let missing = missing_features();
    (!missing.is_empty()).then(|| {
        format!(
            "this build of lumis uses CPU instructions this processor lacks ({}); rebuild it for \
             this CPU with RUSTFLAGS=\"-C target-cpu=native\" cargo build --release",
            missing.join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tests run where they were built, so nothing the build uses can be missing; and, unless
    /// the build's RUSTFLAGS replaced them, the project's build settings (x86-64-v3) really reach
    /// the code (a config file that stopped applying would silently lose the speed measured in
    /// docs/performance.md).
    #[test]
    fn the_build_uses_x86_64_v3_and_this_cpu_has_it() {
        assert_eq!(missing_features(), Vec::<&str>::new());
        #[cfg(target_arch = "x86_64")]
        if option_env!("RUSTFLAGS").is_none() {
            let built_with = [cfg!(target_feature = "avx2"), cfg!(target_feature = "fma")];
            assert_eq!(
                built_with,
                [true, true],
                "built without AVX2/FMA (avx2, fma)"
            );
        }
    }
}
