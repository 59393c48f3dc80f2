// Power-proportional light selection, the twin of `lights/light_sampler.rs` (a
// `DiscreteDistribution` over `Light::power`). The CDF (n + 1 entries, from f64 sums) and the pmf
// (n entries) live in `tables` at offsets given by the parameters.

struct LightChoice {
    index: u32,
    pmf: f32,
}

// Largest i with cdf[i] ≤ u (zero-weight entries own empty intervals and are never returned).
fn light_sampler_sample(cdf_offset: u32, pmf_offset: u32, n: u32, u: f32) -> LightChoice {
    var lo = 0u;
    var hi = n;
    // Invariant: cdf[lo] ≤ u < cdf[hi].
    while hi - lo > 1u {
        let mid = (lo + hi) / 2u;
        if tables[cdf_offset + mid] <= u {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return LightChoice(lo, tables[pmf_offset + lo]);
}

fn light_sampler_pmf(pmf_offset: u32, i: u32) -> f32 {
    return tables[pmf_offset + i];
}
