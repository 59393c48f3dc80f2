// The unidirectional path tracer, the twin of `integrator/path.rs` (one loop, five direct-light
// strategies, Mitsuba's max_depth, Russian roulette from rr_depth, transmission through
// dielectrics under HAS_TRANSMISSION only, so a scene without glass runs the reflection-only
// program, shading normals under HAS_SHADING_NORMALS only, textured materials and emission under
// HAS_TEXTURES only, every random number from its named sampler dimension, `sampler/mod.wgsl`).
// The render kernel that calls `radiance` is `gpu/film.wgsl`.

// `EmissionWeight`: 0 one, 1 zero, 2 MIS, 3 mixture (BSDF branch), 4 fixed (mis-optimal's first
// vertex worked it out; the weight travels in `p_bsdf`). Local to this kernel, not in the prelude:
// the CPU's enum carries its data and no record or parameter holds these.
const EW_ONE: u32 = 0u;
const EW_ZERO: u32 = 1u;
const EW_MIS: u32 = 2u;
const EW_MIXTURE: u32 = 3u;
const EW_FIXED: u32 = 4u;

// Weight of emission from light `light` found by a BSDF-sampled ray (`emission_weight`);
// `light_pdf` is the solid-angle pdf light sampling would have had for the direction; `prev_p`,
// `prev_ns`: the previous vertex, which the light BVH's selection probability depends on;
// `heuristic`: EW_MIS's.
fn emission_weight(rule: u32, p_bsdf: f32, light: u32, light_pdf: f32, prev_p: vec3f, prev_ns: vec3f, heuristic: u32) -> f32 {
    if rule == EW_ONE {
        return 1.0;
    } else if rule == EW_ZERO {
        return 0.0;
    } else if rule == EW_FIXED {
        return p_bsdf;
    }
    var pmf = 0.0;
// #if HAS_LIGHTS
    if params.light_pmf != NONE {
        pmf = light_select_pmf(prev_p, prev_ns, light);
    }
// #endif
    let p_light = pmf * light_pdf;
    if rule == EW_MIS {
        return mis_weight(heuristic, p_bsdf, p_light);
    }
    let w = params.mix_weight;
    let r = p_bsdf / (w * p_light + (1.0 - w) * p_bsdf);
    if is_finite_f(r) {
        return r;
    }
    return 0.0;
}

// #if HAS_SHADING_NORMALS
// The shading-normal rule (`same_side`): a direction counts only if the geometric normal n puts
// it on the side the shading frame does (local_z, its cosine there), and not in the plane.
fn same_side(w: vec3f, n: vec3f, local_z: f32) -> bool {
    let d = dot(w, n);
    return d != 0.0 && ((d > 0.0) == (local_z > 0.0));
}
// #endif

// `LightSampling::receiver_normal` of a vertex with material m and shading normal ns.
fn light_receiver_normal(m: Material, ns: vec3f) -> vec3f {
// #if HAS_TRANSMISSION
    return light_sampling_receiver_normal(params.light_sampling, ns, material_transmits(m));
// #else
    return ns;
// #endif
}

// #if HAS_LIGHTS
// What next-event estimation returns (`direct_light`'s pair): the contribution and, for
// mis-optimal's control variate, whether the sample ended on an outcome BSDF sampling can produce
// too (`NeeOutcome::Combined`) with its balance ratios.
struct NeeResult {
    c: vec3f,
    combined: bool,
    rl: f32,
    rb: f32,
}

fn nee_pure() -> NeeResult {
    return NeeResult(vec3f(0.0), false, 0.0, 0.0);
}

// `shadow_ray`: from hit (geometric normal n) to the light sample ls, to infinity for a light
// at infinity.
fn shadow_ray(hit: SurfaceHit, n: vec3f, ls: LightSample) -> Ray {
    if ls.infinite {
        return spawn_ray(hit.p, hit.p_error, n, ls.wi);
    }
    return spawn_ray_to(hit.p, hit.p_error, n, ls.p, ls.p_error, ls.n);
}

// Next-event estimation (`direct_light`); `mixture_w` ≥ 0 on the mixture's light branch; `mis_h`
// the MIS heuristic or NONE (light sampling alone); `cv`: mis-optimal's control variate needs the
// outcome; `shading`: the frame is a shading normal's (the rule above applies).
// #if HAS_SHADING_NORMALS
fn direct_light(hit: SurfaceHit, n: vec3f, frame: Frame, wo: vec3f, m: Material, u_light: f32, u: vec2f, mixture_w: f32, mis_h: u32, cv: bool, shading: bool) -> NeeResult {
// #else
fn direct_light(hit: SurfaceHit, n: vec3f, frame: Frame, wo: vec3f, m: Material, u_light: f32, u: vec2f, mixture_w: f32, mis_h: u32, cv: bool) -> NeeResult {
// #endif
    let choice = light_select(hit.p, frame.n, u_light);
    if !(choice.pmf > 0.0) {
        return nee_pure();
    }
    let light = lights[choice.index];
    var ls = light_sample(light, hit.p, light_receiver_normal(m, frame.n), u, params.light_sampling);
// #if HAS_TEXTURES
    ls = light_sample_textured(light, ls);
// #endif
    if !ls.ok {
        return nee_pure();
    }
    let wi = to_local(frame, ls.wi);
// #if HAS_TRANSMISSION
    // A dielectric's lights may lie on either side.
    if select(wi.z <= 0.0, wi.z == 0.0, material_transmits(m)) {
// #else
    if wi.z <= 0.0 {
// #endif
        return nee_pure();
    }
// #if HAS_SHADING_NORMALS
    if shading && !same_side(ls.wi, n, wi.z) {
        return nee_pure();
    }
// #endif
    let f = vertex_eval(m, wo, wi);
// #if HAS_DELTA_LIGHT
    if light_is_delta(light) {
        return delta_light(hit, n, ls, f, choice.pmf, mixture_w);
    }
// #endif
    var p_bsdf_cv = 0.0;
    if cv {
        p_bsdf_cv = vertex_pdf(m, wo, wi);
    }
    if all(f == vec3f(0.0)) && p_bsdf_cv <= 0.0 {
        return nee_pure();
    }
    if scene_occluded(shadow_ray(hit, n, ls)) {
        return nee_pure();
    }
    let p_light = choice.pmf * ls.pdf;
    if mixture_w >= 0.0 {
        let p_mix = mixture_w * p_light + (1.0 - mixture_w) * vertex_pdf(m, wo, wi);
        return NeeResult(f * ls.le / p_mix, false, 0.0, 0.0);
    }
    var weight = 1.0;
    if mis_h != NONE {
        var pb = p_bsdf_cv;
        if !cv {
            pb = vertex_pdf(m, wo, wi);
        }
        weight = mis_weight(mis_h, p_light, pb);
    }
    let c = f * ls.le * (weight / p_light);
    if cv {
        let r = balance_ratios(p_light, p_bsdf_cv);
        if r.ok {
            return NeeResult(c, true, r.rl, r.rb);
        }
    }
    return NeeResult(c, false, 0.0, 0.0);
}

// #if HAS_DELTA_LIGHT
// `delta_light`: a delta light's sample ls (selected with probability pmf) at a vertex whose
// BSDF value towards it is f: MIS weight 1, divided by the light branch's probability under the
// mixture (mixture_w ≥ 0); zero where blocked. Pure for mis-optimal, marked by rl = −1 (its
// contribution goes to the moments, `opt_delta_light`).
fn delta_light(hit: SurfaceHit, n: vec3f, ls: LightSample, f: vec3f, pmf: f32, mixture_w: f32) -> NeeResult {
    if all(f == vec3f(0.0)) {
        return NeeResult(vec3f(0.0), false, -1.0, 0.0);
    }
    if scene_occluded(shadow_ray(hit, n, ls)) {
        return NeeResult(vec3f(0.0), false, -1.0, 0.0);
    }
    var branch = 1.0;
    if mixture_w >= 0.0 {
        branch = mixture_w;
    }
    return NeeResult(f * ls.le / (pmf * branch), false, -1.0, 0.0);
}
// #endif

// mis-optimal: resolves the first vertex's pending BSDF sample (`resolve_bsdf`; throughput
// `beta` at the vertex, sample weight `weight`, pdf `pdf`, `delta`) once its `ray` found `hit`:
// records it in the sample's moments; returns its control-variate term and the weight of the
// emission it found.
struct Resolved {
    cv: vec3f,
    w: f32,
}

fn resolve_bsdf(ray: Ray, hit: SurfaceHit, prev_p: vec3f, prev_ns: vec3f, prev_light_ns: vec3f, beta: vec3f, weight: vec3f, pdf: f32, delta: bool) -> Resolved {
    var le = vec3f(0.0);
    var p_light = 0.0;
    if hit.prim == NONE {
// #if HAS_BACKGROUND
        if params.background != NONE {
            let bg = lights[params.background];
            le = light_radiance(bg, vec3f(0.0), ray.d);
            if !delta && params.light_pmf != NONE {
                p_light = light_select_pmf(prev_p, prev_ns, params.background)
                    * light_pdf(bg, prev_p, prev_light_ns, ray.d, vec3f(0.0), vec3f(0.0), params.light_sampling);
            }
        }
// #endif
    } else {
        let prim = prims[hit.prim];
        let li = prim_light(prim);
        if li != NONE {
            let light = lights[li];
            le = light_radiance(light, hit.n, ray.d);
// #if HAS_TEXTURES
            le = light_emitted(light, prim, hit, le);
// #endif
            if !delta && params.light_pmf != NONE {
                p_light = light_select_pmf(prev_p, prev_ns, li)
                    * light_pdf(light, prev_p, prev_light_ns, normalize_glam(ray.d), hit.p, hit.n, params.light_sampling);
            }
        }
    }
    if delta {
        return Resolved(beta * opt_pure_bsdf(weight * le), 1.0);
    }
    let emits = any(le > vec3f(0.0));
    let r = balance_ratios(p_light, pdf);
    if r.ok && emits && p_light > 0.0 {
        return Resolved(beta * opt_combined(weight * le * r.rb, r.rl, r.rb), r.rb);
    }
    let w = mis_weight(HEURISTIC_BALANCE, pdf, p_light);
    return Resolved(beta * opt_pure_bsdf(weight * le * w), w);
}
// #endif

fn radiance(camera_ray: Ray) -> vec3f {
    var ray = camera_ray;
    let max_depth = params.max_depth;
    var l = vec3f(0.0);
    var beta = vec3f(1.0);
// #if HAS_TRANSMISSION
    // Product of η'² over the refractions so far: Russian roulette sees beta·eta_scale.
    var eta_scale = 1.0;
// #endif
    var rule = EW_ONE;
    var p_bsdf = 0.0;
    // EW_MIS's heuristic.
    var mis_h = params.heuristic;
    var prev_p = ray.o;
    // The previous vertex's shading normal, for light selection (zero at the camera), and the
    // one it gave the light sampler (`light_receiver_normal`), for the light pdf.
    var prev_ns = vec3f(0.0);
    var prev_light_ns = vec3f(0.0);
    var depth = 0;
    // mis-optimal: the first vertex's BSDF sample awaiting its hit (`PendingBsdf`), and whether
    // the path ends once it is resolved (roulette or a zero throughput would have ended it).
    var pending = false;
    var pend_beta = vec3f(0.0);
    var pend_weight = vec3f(0.0);
    var pend_pdf = 0.0;
    var pend_delta = false;
    var stop = false;
    loop {
        depth += 1;
        // The sampler's bounce: 0 at the camera ray's hit.
        let bounce = u32(depth - 1);
        let hit = scene_intersect(ray);
// #if HAS_LIGHTS
        if pending {
            pending = false;
            let res = resolve_bsdf(ray, hit, prev_p, prev_ns, prev_light_ns, pend_beta, pend_weight, pend_pdf, pend_delta);
            l += res.cv;
            rule = EW_FIXED;
            p_bsdf = res.w;
            if stop {
                break;
            }
        }
// #endif
        // Mitsuba's hide_emitters: what the camera ray hits does not count its emission.
        let hidden = params.hide_emitters != 0u && depth == 1;
        if hit.prim == NONE {
// #if HAS_BACKGROUND
            if params.background != NONE && !hidden {
                let bg = lights[params.background];
                // The pdf light sampling would have had for this direction, with the method in
                // use (a constant background's is 1/4π either way).
                var lpdf = 0.0;
// #if HAS_LIGHTS
                if rule == EW_MIS || rule == EW_MIXTURE {
                    lpdf = light_pdf(bg, prev_p, prev_light_ns, ray.d, vec3f(0.0), vec3f(0.0), params.light_sampling);
                }
// #endif
                let w = emission_weight(rule, p_bsdf, params.background, lpdf, prev_p, prev_ns, mis_h);
                l += beta * light_radiance(bg, vec3f(0.0), ray.d) * w;
            }
// #endif
            break;
        }
        let prim = prims[hit.prim];
        let light_index = prim_light(prim);
        if light_index != NONE && !hidden {
            let light = lights[light_index];
            var le = light_radiance(light, hit.n, ray.d);
// #if HAS_TEXTURES
            le = light_emitted(light, prim, hit, le);
// #endif
            if any(le != vec3f(0.0)) {
                var lpdf = 0.0;
// #if HAS_LIGHTS
                if rule == EW_MIS || rule == EW_MIXTURE {
                    lpdf = light_pdf(light, prev_p, prev_light_ns, normalize_glam(ray.d), hit.p, hit.n, params.light_sampling);
                }
// #endif
                l += beta * le * emission_weight(rule, p_bsdf, light_index, lpdf, prev_p, prev_ns, mis_h);
            }
        }
        if max_depth >= 0 && depth >= max_depth {
            break;
        }
        let wo_world = -normalize_glam(ray.d);
// #if HAS_MIXES
        // `Scene::resolve`: mixes and two-sided pairs choose one of their materials at the hit
        // (a pair by the side the path arrives on).
        let resolved = material_resolve(prim_material(prim), prim, hit, dot(hit.n, wo_world) < 0.0);
        let mi = resolved.index;
// #else
        let mi = prim_material(prim);
// #endif
        var m = materials[mi];
// #if HAS_TEXTURES
        // `Scene::shading_at`: the hit's texture coordinates, once for the material's textures
        // and its normal or bump map.
        var at = tex_uv(vec2f(0.0));
        var needs_uv = material_textured(m);
// #if HAS_NORMAL_MAPS
        needs_uv = needs_uv || normal_map_texture(m) != 0u;
// #endif
        if needs_uv {
            at = surface_tex(prim, hit);
        }
        if material_textured(m) {
            m = material_at(m, at);
        }
// #endif
        // `n`: the geometric normal, which decides sides and ray offsets; the BSDF lives in the
        // frame of the shading normal `ns` (the geometric one where the mesh has none).
        var n = hit.n;
// #if HAS_NORMAL_MAPS
        // The path sees the back of a two-sided material (`normal_map_seen_from`).
        var back = false;
// #endif
// #if HAS_SHADING_NORMALS
        let sn = shading_normal(prim_attr(prim), hit.b, n);
        let shading = sn.found;
        var ns = sn.n;
// #endif
// #if HAS_TRANSMISSION
        // A dielectric's frame is never flipped: wo below it means the viewer is inside.
        let transmits = material_transmits(m);
        if dot(n, wo_world) < 0.0 && !transmits {
// #else
        if dot(n, wo_world) < 0.0 {
// #endif
            // Bit 0 of h.y: two-sided (`materials/normal_map.wgsl` has the others); a material
            // that a pair chose is seen from either side.
            var two_sided = (m.h.y & 1u) != 0u;
// #if HAS_MIXES
            two_sided = two_sided || resolved.paired;
// #endif
            if !two_sided {
                break;
            }
// #if HAS_NORMAL_MAPS
            back = true;
// #endif
            n = -n;
// #if HAS_SHADING_NORMALS
            ns = -ns;
// #endif
        }
// #if HAS_SHADING_NORMALS
        var frame = frame_from_normal(ns);
// #else
        var frame = frame_from_normal(n);
// #endif
// #if HAS_ANISOTROPIC
        // An anisotropic lobe's α_u runs along the surface's ∂p/∂u (`geometry/tangent.wgsl`).
        if material_anisotropic(m) {
            frame = tangent_frame(frame.n, surface_dp_du(prim, hit));
        }
// #endif
// #if HAS_NORMAL_MAPS
        // A normal or bump map tilts the frame the material sees, about the frame of ∂p/∂u
        // (`materials/normal_map.wgsl`).
        vertex_perturbation = no_perturbation();
        let nm = normal_map_texture(m);
        if nm != 0u {
            var tilt = vec4f(0.0);
            // A bump map's ∂p/∂u, kept for the base frame (`triangle_dp_duv`'s is `surface_dp_du`'s).
            var dp_du = vec3f(0.0);
            let bump = normal_map_is_bump(m);
            if bump {
                // In the front's frame, which `seen_from` mirrors on the back as for a texel.
                let scale = texture_record(nm - 1u).c1.x;
                let d = triangle_dp_duv(prim, hit);
                let ns_front = select(frame.n, -frame.n, back);
                let front = tangent_frame(ns_front, d.du);
                dp_du = d.du;
                tilt = bump_normal(scale * texture_eval_1_grad(nm - 1u, at.uv), d.du, d.dv, ns_front, hit.n, front);
            } else {
                tilt = vec4f(2.0 * texture_eval(nm - 1u, at) - vec3f(1.0), 1.0);
            }
            if tilt.w != 0.0 {
                if !bump {
                    dp_du = surface_dp_du(prim, hit);
                }
                let base = normal_map_seen_from(tangent_frame(frame.n, dp_du), back);
                let pert = normal_map_perturb(m.h.y, tilt.xyz, base, wo_world);
                if pert.ok {
                    frame = pert.frame;
                    vertex_perturbation = pert.p;
                }
            }
        }
// #endif
        let wo = to_local(frame, wo_world);
// #if HAS_TRANSMISSION
        // A reflecting surface is seen from its front only; a dielectric from either side.
        if select(wo.z <= 0.0, wo.z == 0.0, transmits) {
// #else
        if wo.z <= 0.0 {
// #endif
            break;
        }
// #if HAS_SHADING_NORMALS
        if shading && !same_side(wo_world, n, wo.z) {
            break;
        }
// #endif

        // Direct light by light sampling, and the rule for emission the BSDF sample will find.
        var do_nee = false;
        var nee_mixture_w = -1.0;
        rule = EW_ONE;
        // mis-optimal's first vertex: the balance heuristic plus the control variate (the GPU
        // engine always supplies α).
        let optimal_vertex = depth == 1 && params.strategy == STRATEGY_MIS_OPTIMAL;
        var cv = false;
// #if HAS_LIGHTS
        let nee_worth = material_has_smooth_part(m) && params.light_cdf != NONE;
        if nee_worth {
            switch params.strategy {
                case STRATEGY_LIGHT: {
                    do_nee = true;
                    rule = EW_ZERO;
                    mis_h = NONE;
                }
                case STRATEGY_MIS: {
                    do_nee = true;
                    rule = EW_MIS;
                    p_bsdf = 0.0;
                    mis_h = params.heuristic;
                }
                case STRATEGY_MIS_OPTIMAL: {
                    do_nee = true;
                    rule = EW_MIS;
                    p_bsdf = 0.0;
                    mis_h = select(HEURISTIC_POWER, HEURISTIC_BALANCE, optimal_vertex);
                    cv = optimal_vertex;
                }
                case STRATEGY_MIXTURE: {
                    if sampler_mixture_1d(bounce) < params.mix_weight {
                        do_nee = true;
                        nee_mixture_w = params.mix_weight;
                        rule = EW_ZERO;
                    } else {
                        rule = EW_MIXTURE;
                        p_bsdf = 0.0;
                    }
                }
                case STRATEGY_BSDF: {}
                default: {
                    _ = unknown_tag();
                }
            }
        }
        if do_nee {
            let u_light = sampler_light_select_1d(bounce);
            let u = sampler_light_2d(bounce);
            var nee_h = mis_h;
            if nee_mixture_w >= 0.0 {
                nee_h = NONE;
            }
// #if HAS_SHADING_NORMALS
            let nee = direct_light(hit, n, frame, wo, m, u_light, u, nee_mixture_w, nee_h, cv, shading);
// #else
            let nee = direct_light(hit, n, frame, wo, m, u_light, u, nee_mixture_w, nee_h, cv);
// #endif
            l += beta * nee.c;
            if cv {
                var term = vec3f(0.0);
                if nee.combined {
                    term = opt_combined(nee.c, nee.rl, nee.rb);
                } else {
// #if HAS_DELTA_LIGHT
                    if nee.rl < 0.0 {
                        term = opt_delta_light(nee.c);
                    } else {
                        term = opt_pure_light();
                    }
// #else
                    term = opt_pure_light();
// #endif
                }
                l += beta * (opt_constant() + term);
            }
        }
// #endif

        // Continue the path by BSDF sampling.
        let u_lobe = sampler_bsdf_lobe_1d(bounce);
        var bs = vertex_sample(m, wo, u_lobe, sampler_bsdf_2d(bounce));
// #if HAS_MIXES
        // Mitsuba's blend weighs a delta sample against the other part there (`materials/mix.rs`).
        if bs.ok && bs.delta && resolved.partner != NONE {
            var pm = materials[resolved.partner];
// #if HAS_TEXTURES
            if material_textured(pm) {
                pm = material_at(pm, surface_tex(prim, hit));
            }
// #endif
            let f = material_eval(pm, wo, bs.wi);
            let p = material_pdf(pm, wo, bs.wi);
            bs.weight = blend_delta_weight(bs.weight, bs.pdf, resolved.weight, f, p);
        }
// #endif
        if !bs.ok {
            if cv {
                l += beta * opt_pure_bsdf(vec3f(0.0));
            }
            break;
        }
        let wi = to_world(frame, bs.wi);
        var wi_ok = true;
// #if HAS_SHADING_NORMALS
        wi_ok = !(shading && !same_side(wi, n, bs.wi.z));
// #endif
        if cv {
            if wi_ok {
                pending = true;
                pend_beta = beta;
                pend_weight = bs.weight;
                pend_pdf = bs.pdf;
                pend_delta = bs.delta;
            } else {
                l += beta * opt_pure_bsdf(vec3f(0.0));
            }
        }
        if bs.delta {
            rule = EW_ONE;
        } else {
            p_bsdf = bs.pdf;
        }
        beta *= bs.weight;
// #if HAS_TRANSMISSION
        eta_scale *= bs.eta * bs.eta;
// #endif
        if !wi_ok || (all(beta == vec3f(0.0)) && !pending) {
            break;
        }
        prev_p = hit.p;
        prev_ns = frame.n;
        prev_light_ns = light_receiver_normal(m, frame.n);
        ray = spawn_ray(hit.p, hit.p_error, n, wi);
        if all(beta == vec3f(0.0)) {
            // Traced only for the pending control variate.
            stop = true;
            continue;
        }

        if u32(depth) >= params.rr_depth {
// #if HAS_TRANSMISSION
            let q = min(max_component(beta * eta_scale), 0.95);
// #else
            let q = min(max_component(beta), 0.95);
// #endif
            if sampler_rr_1d(bounce) >= q {
                if !pending {
                    break;
                }
                stop = true;
                continue;
            }
            beta /= q;
        }
    }
    return l;
}
