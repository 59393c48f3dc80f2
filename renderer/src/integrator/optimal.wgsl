// Optimal MIS weights (`mis-optimal`), the twin of `integrator/optimal.rs`: the balance ratios of
// an outcome both techniques can produce, the control-variate terms of one sample (its α and
// moments live in private variables that `render` in `gpu/film.wgsl` loads and stores), the stage
// schedule and the 2×2 solve for α. The moments are f32 sums here (f64 on the CPU): α differs
// by rounding, which only changes the variance, never the expected value.

// α of light and BSDF sampling for this sample, per channel.
var<private> opt_alpha_l: vec3f;
var<private> opt_alpha_b: vec3f;
// This sample's moments: M_LL, M_LB, M_BB, and b_L, b_B per channel.
var<private> opt_m: vec3f;
var<private> opt_bl: vec3f;
var<private> opt_bb: vec3f;

// `balance_ratios`: (r_L, r_B) where both pdfs are finite, non-negative and not both zero.
struct Ratios {
    ok: bool,
    rl: f32,
    rb: f32,
}

fn balance_ratios(p_light: f32, p_bsdf: f32) -> Ratios {
    let ok = is_finite_f(p_light) && p_light >= 0.0 && is_finite_f(p_bsdf) && p_bsdf >= 0.0
        && p_light + p_bsdf > 0.0;
    if !ok {
        return Ratios(false, 0.0, 0.0);
    }
    return Ratios(true, mis_weight(HEURISTIC_BALANCE, p_light, p_bsdf), mis_weight(HEURISTIC_BALANCE, p_bsdf, p_light));
}

// `OptimalSample::constant`: α_L + α_B.
fn opt_constant() -> vec3f {
    return opt_alpha_l + opt_alpha_b;
}

// `OptimalSample::combined`: records the sample and returns −α·r.
fn opt_combined(c: vec3f, rl: f32, rb: f32) -> vec3f {
    opt_m += vec3f(rl * rl, rl * rb, rb * rb);
    opt_bl += c * rl;
    opt_bb += c * rb;
    return -(opt_alpha_l * rl + opt_alpha_b * rb);
}

// `OptimalSample::pure_light`: returns −α_L.
fn opt_pure_light() -> vec3f {
    opt_m.x += 1.0;
// #if MUTANTS
    if MUTANT_OPTIMAL_PURE_ZERO == 1u {
        return vec3f(0.0);
    }
// #endif
    return -opt_alpha_l;
}

// #if HAS_DELTA_LIGHT
// `OptimalSample::delta_light`: a delta light's sample of contribution h (pure); returns −α_L.
fn opt_delta_light(h: vec3f) -> vec3f {
    opt_m.x += 1.0;
    opt_bl += h;
// #if MUTANTS
    if MUTANT_OPTIMAL_PURE_ZERO == 1u {
        return vec3f(0.0);
    }
// #endif
    return -opt_alpha_l;
}
// #endif

// `OptimalSample::pure_bsdf`: a pure BSDF sample of contribution h; returns −α_B.
fn opt_pure_bsdf(h: vec3f) -> vec3f {
    opt_m.z += 1.0;
    opt_bb += h;
// #if MUTANTS
    if MUTANT_OPTIMAL_PURE_ZERO == 1u {
        return vec3f(0.0);
    }
// #endif
    return -opt_alpha_b;
}

// `is_stage_start`.
fn opt_is_stage_start(s: u32) -> bool {
    return s >= OPTIMAL_FIRST_STAGE && (s & (s - 1u)) == 0u;
}

struct Alpha {
    light: vec3f,
    bsdf: vec3f,
}

// `Moments::solve`: (M + λI) α = b per channel, λ = OPTIMAL_RIDGE · trace(M); α = 0 where M is
// empty or anything is not finite.
fn optimal_solve(m: vec3f, bl: vec3f, bb: vec3f) -> Alpha {
    let zero = Alpha(vec3f(0.0), vec3f(0.0));
    let trace = m.x + m.z;
    if !(trace > 0.0 && is_finite_f(trace)) {
        return zero;
    }
    let lambda = OPTIMAL_RIDGE * trace;
    let a = m.x + lambda;
    let d = m.z + lambda;
    let c = m.y;
    let det = a * d - c * c;
    if !(det > 0.0 && is_finite_f(det)) {
        return zero;
    }
    let al = (d * bl - c * bb) / det;
    let ab = (a * bb - c * bl) / det;
    if !(is_finite3(al) && is_finite3(ab)) {
        return zero;
    }
    return Alpha(al, ab);
}
