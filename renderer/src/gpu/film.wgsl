// The render kernel, the twin of the CPU's render loop and film (`engine.rs`): each invocation
// draws samples of one pixel from the integrator (`integrator/path.wgsl`, `radiance`) and folds
// them into the accumulation with Welford's update (stable variance in f32; the film reads back Σx
// and Σx² from it), with mis-optimal's per-pixel moments beside it.

// mis-optimal's planes of `accum` (`GpuProgressive`): after the three of the film, the pixel's
// moments (M_LL, M_LB, M_BB), b_L, b_B, then α_L, α_B of its current stage; the scratch planes
// of multi-sample dispatches follow them.
const OPT_PLANES: u32 = 5u;

fn optimal_on() -> bool {
    return params.strategy == STRATEGY_MIS_OPTIMAL;
}

// First scratch plane: after the film's three and, for mis-optimal, its OPT_PLANES.
fn scratch_base() -> u32 {
    return 3u + select(0u, OPT_PLANES, optimal_on());
}

// `PixelState::alpha_for`, for every sample of this dispatch (the host splits dispatches where a
// stage starts, so a stage starts at most at the dispatch's first sample): there α comes from the
// moments of samples 0..params.sample, which no invocation writes during the dispatch, and layer
// 0 stores it; elsewhere the stage's stored α. Zeroes the sample's moments.
fn opt_load(pixel: u32, layer: u32) {
    let plane = params.width * params.height;
    opt_m = vec3f(0.0);
    opt_bl = vec3f(0.0);
    opt_bb = vec3f(0.0);
    if opt_is_stage_start(params.sample) {
        let a = optimal_solve(accum[3u * plane + pixel].xyz, accum[4u * plane + pixel].xyz, accum[5u * plane + pixel].xyz);
        opt_alpha_l = a.light;
        opt_alpha_b = a.bsdf;
        if layer == 0u {
            accum[6u * plane + pixel] = vec4f(a.light, 0.0);
            accum[7u * plane + pixel] = vec4f(a.bsdf, 0.0);
        }
    } else {
        opt_alpha_l = accum[6u * plane + pixel].xyz;
        opt_alpha_b = accum[7u * plane + pixel].xyz;
    }
}

// Adds moments to the pixel's sums.
fn opt_add(pixel: u32, m: vec3f, bl: vec3f, bb: vec3f) {
    let plane = params.width * params.height;
    accum[3u * plane + pixel] = vec4f(accum[3u * plane + pixel].xyz + m, 0.0);
    accum[4u * plane + pixel] = vec4f(accum[4u * plane + pixel].xyz + bl, 0.0);
    accum[5u * plane + pixel] = vec4f(accum[5u * plane + pixel].xyz + bb, 0.0);
}

// One dispatch renders `params.samples_per_dispatch` samples per pixel, one per z layer: small
// images then still fill a large GPU (256² pixels are a quarter of the threads an H100 holds).
// With one layer the sample is added at once; with more, each layer leaves its radiance (and
// mis-optimal's moments) in scratch planes and `fold` adds them in sample order with the same
// updates, so the image is the same bit for bit whatever the layering.
@compute @workgroup_size(8, 8, 1)
fn render(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let pixel = gid.y * params.width + gid.x;
    let s = params.sample + gid.z;
    let optimal = optimal_on();
    if optimal {
        opt_load(pixel, gid.z);
    }
    // `Sampler::new`, as the CPU's render loop makes it (`engine.rs`); an unknown sampler tag
    // flags the sample there.
    sampler_init(params.sampler, params.seed, gid.x, gid.y, params.width, s);
    check_param_tags(params);
    // `Camera::film_sample`: the box filter's jitter over the pixel or another filter's film
    // position, from the camera's 2-D sample either way, and the sample's weight (1 but for a
    // filter with negative lobes; the optimal-MIS moments stay unweighted, as the CPU's).
    let film = film_position(params_filter(), sampler_camera_2d(), gid.x, gid.y, params.width, params.height);
    var x = radiance(camera_ray(film.xy)) * film.z;
    if unknown_tag_seen {
        // A record or parameter with a tag no `switch` knows (`gpu/prelude.wgsl`): a NaN sample.
        x = vec3f(unknown_tag());
    }
    // A dropped sample adds nothing to the moments either (`engine.rs`).
    let keep_moments = is_finite3(x) && is_finite3(opt_m) && is_finite3(opt_bl) && is_finite3(opt_bb);
    if !is_finite3(x) {
        // The CPU skips it but still counts the sample: a zero sample.
        atomicAdd(&counters[0], 1u);
        x = vec3f(0.0);
    }
    if !keep_moments {
        opt_m = vec3f(0.0);
        opt_bl = vec3f(0.0);
        opt_bb = vec3f(0.0);
    }
    let plane = params.width * params.height;
    if params.samples_per_dispatch == 1u {
        accumulate(pixel, s, x);
        if optimal {
            opt_add(pixel, opt_m, opt_bl, opt_bb);
        }
    } else {
        let base = scratch_base();
        accum[(base + gid.z) * plane + pixel] = vec4f(x, 0.0);
        if optimal {
            // Layer j's moments: three planes after the dispatch's radiance planes.
            let m = base + params.samples_per_dispatch + 3u * gid.z;
            accum[m * plane + pixel] = vec4f(opt_m, 0.0);
            accum[(m + 1u) * plane + pixel] = vec4f(opt_bl, 0.0);
            accum[(m + 2u) * plane + pixel] = vec4f(opt_bb, 0.0);
        }
    }
}

// Adds the layers of a multi-sample dispatch to the accumulation, in sample order.
@compute @workgroup_size(8, 8, 1)
fn fold(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= params.width || gid.y >= params.height {
        return;
    }
    let pixel = gid.y * params.width + gid.x;
    let plane = params.width * params.height;
    let base = scratch_base();
    for (var j = 0u; j < params.samples_per_dispatch; j++) {
        accumulate(pixel, params.sample + j, accum[(base + j) * plane + pixel].xyz);
        if optimal_on() {
            let m = base + params.samples_per_dispatch + 3u * j;
            opt_add(pixel, accum[m * plane + pixel].xyz, accum[(m + 1u) * plane + pixel].xyz, accum[(m + 2u) * plane + pixel].xyz);
        }
    }
}

// Sample `s` (radiance `x`) into the running mean, Welford's M2 and the even-sample mean.
fn accumulate(pixel: u32, s: u32, x: vec3f) {
    let plane = params.width * params.height;
    let mean = accum[pixel].xyz;
    let delta = x - mean;
    let new_mean = mean + delta / f32(s + 1u);
    accum[pixel] = vec4f(new_mean, 0.0);
    accum[plane + pixel] = vec4f(accum[plane + pixel].xyz + delta * (x - new_mean), 0.0);
    if s % 2u == 0u {
        let even = accum[2u * plane + pixel].xyz;
        accum[2u * plane + pixel] = vec4f(even + (x - even) / f32(s / 2u + 1u), 0.0);
    }
}
