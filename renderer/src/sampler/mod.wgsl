// The samplers, the twin of `sampler/mod.rs`: where each random number of a path sample comes
// from. `sampler_init` picks the sampler by its SAMPLER_* tag (`Params::sampler`, in the variant
// order of `SamplerKind`) and every draw goes through one closed `switch` on it: SAMPLER_INDEPENDENT
// is the PCG stream of `rng.wgsl` drawn in call order (the dimension unused, so the path tracer
// draws what it drew before samplers existed), SAMPLER_SOBOL is `sampler/zsobol.wgsl`. An unknown tag
// flags the sample (`gpu/prelude.wgsl`) and draws NaN. The named draws below allocate the dimensions as
// the CPU's table does (DIM_* from the prelude; bounce b = path vertex b + 1, 0 at the first hit).

// The sampler of the sample being drawn.
var<private> sampler_kind: u32;

// `Sampler::new`: sample `sample` of pixel (x, y) of an image `width` pixels wide.
fn sampler_init(kind: u32, seed: u32, x: u32, y: u32, width: u32, sample: u32) {
    sampler_kind = kind;
    switch kind {
        case SAMPLER_INDEPENDENT: {
            rng_init(seed, y * width + x, sample);
        }
        case SAMPLER_SOBOL: {
            zsobol_init(seed, x, y, sample);
        }
        default: {
            _ = unknown_tag();
        }
    }
}

// `Sampler::get_1d`.
fn sampler_get_1d(dim: u32) -> f32 {
    switch sampler_kind {
        case SAMPLER_INDEPENDENT: {
            return rng_next_f32();
        }
        case SAMPLER_SOBOL: {
            return zsobol_get_1d(dim);
        }
        default: {
            return unknown_tag();
        }
    }
}

// `Sampler::get_2d`: dimensions dim and dim + 1.
fn sampler_get_2d(dim: u32) -> vec2f {
    switch sampler_kind {
        case SAMPLER_INDEPENDENT: {
            return rng_next_2d();
        }
        case SAMPLER_SOBOL: {
            return zsobol_get_2d(dim);
        }
        default: {
            return vec2f(unknown_tag());
        }
    }
}

// `dim::at`: the dimension of `offset` at bounce `bounce` (u32 wraps as Rust's wrapping ops).
fn sampler_dim(bounce: u32, offset: u32) -> u32 {
    return DIM_FIRST_BOUNCE + bounce * DIM_PER_BOUNCE + offset;
}

// `Sampler::camera_2d`: the film position.
fn sampler_camera_2d() -> vec2f {
    return sampler_get_2d(DIM_CAMERA);
}

// `Sampler::lens_2d`: the thin lens's point on the lens.
fn sampler_lens_2d() -> vec2f {
    return sampler_get_2d(DIM_LENS);
}

// `Sampler::mixture_1d`: the one-sample mixture's branch.
fn sampler_mixture_1d(bounce: u32) -> f32 {
    return sampler_get_1d(sampler_dim(bounce, DIM_MIXTURE));
}

// `Sampler::light_select_1d`.
fn sampler_light_select_1d(bounce: u32) -> f32 {
    return sampler_get_1d(sampler_dim(bounce, DIM_LIGHT_SELECT));
}

// `Sampler::light_2d`: the point on the light.
fn sampler_light_2d(bounce: u32) -> vec2f {
    var d = sampler_dim(bounce, DIM_LIGHT);
// #if MUTANTS
    if MUTANT_SAMPLER_LIGHT_CAMERA != 0u {
        d = DIM_CAMERA;
    }
// #endif
    return sampler_get_2d(d);
}

// `Sampler::bsdf_lobe_1d`.
fn sampler_bsdf_lobe_1d(bounce: u32) -> f32 {
    return sampler_get_1d(sampler_dim(bounce, DIM_BSDF_LOBE));
}

// `Sampler::bsdf_2d`: the BSDF direction.
fn sampler_bsdf_2d(bounce: u32) -> vec2f {
    var b = bounce;
// #if MUTANTS
    if MUTANT_SAMPLER_SHARED_BOUNCES != 0u {
        b = 0u;
    }
// #endif
    return sampler_get_2d(sampler_dim(b, DIM_BSDF));
}

// `Sampler::rr_1d`: Russian roulette.
fn sampler_rr_1d(bounce: u32) -> f32 {
    return sampler_get_1d(sampler_dim(bounce, DIM_RR));
}
