// The scene and render bindings shared by every kernel (group 0), uploaded by `gpu/scene/mod.rs`;
// the per-sample parameters (`gpu/scene/params.rs`) arrive through a dynamic uniform offset.

struct Params {
    width: u32,
    height: u32,
    seed: u32,
    sample: u32,
    // STRATEGY_*, HEURISTIC_*, LIGHT_SAMPLING_*.
    strategy: u32,
    heuristic: u32,
    light_sampling: u32,
    max_depth: i32,
    rr_depth: u32,
    n_lights: u32,
    // Index of the background light, or NONE.
    background: u32,
    // Offsets of the light-selection CDF and pmf in `tables`; NONE when nothing can be sampled.
    light_cdf: u32,
    light_pmf: u32,
    mix_weight: f32,
    // Samples of this dispatch (its z layers), from `sample` on (`gpu/film.wgsl`, `fold`).
    samples_per_dispatch: u32,
    // Where the texture records start in `vertex_data` (`textures/mod.wgsl`).
    textures: u32,
    // Camera (`camera.wgsl`): origin, forward, right, up; the film's half-extents in origin.w,
    // forward.w; the thin lens's aperture radius and focus distance in right.w, up.w.
    cam_origin: vec4f,
    cam_forward: vec4f,
    cam_right: vec4f,
    cam_up: vec4f,
    // The principal point offset in pixels in xy (`Camera::shift`).
    cam_shift: vec4f,
    // Where the mesh attribute arrays start in `vertex_data` (triangles, meshes, normals, uvs).
    attr: vec4<u32>,
    // The camera's pixel filter (FILTER_*), the gaussian's σ and the radius in pixels
    // (`camera/filter.wgsl`).
    pixel_filter: u32,
    filter_stddev: f32,
    filter_radius: f32,
    // The sampler (SAMPLER_*, `sampler/mod.wgsl`, which fails an unknown one); also rounds the
    // struct to the 16 bytes a uniform's size is a multiple of, as `GpuParams` does.
    sampler: u32,
    // Light selection (LIGHT_SELECTION_*, `lights/light_bvh.wgsl`) and the light BVH's offset in
    // `tables` (NONE when nothing can be sampled); the struct's size rounds up to 16 bytes.
    light_selection: u32,
    light_bvh: u32,
    // 1: camera rays do not see emitters (Mitsuba's hide_emitters, `integrator/path.wgsl`).
    hide_emitters: u32,
    // The camera's projection (CAMERA_*, `camera.wgsl`, which fails an unknown one); it took the
    // slot that rounded the struct to 16 bytes.
    camera: u32,
    // A Mitchell filter's B and C in xy, and its piece ends on [0, 2] (`camera/filter.wgsl`).
    filter_shape: vec4f,
    filter_breaks: array<vec4f, 2>,
}

// The camera's pixel filter (`film_position` in `camera/filter.wgsl`; an unknown tag fails there).
fn params_filter() -> PixelFilter {
    return PixelFilter(params.pixel_filter, params.filter_stddev, params.filter_radius,
        params.filter_shape.x, params.filter_shape.y, params.filter_breaks[0], params.filter_breaks[1]);
}

// Flags the sample when `p` holds a tag `gpu/scene/params.rs` never writes (the heuristic and the
// light-sampling method are read by `if`s that would take any other value for the second).
fn check_param_tags(p: Params) {
    switch p.strategy {
        case STRATEGY_LIGHT, STRATEGY_BSDF, STRATEGY_MIXTURE, STRATEGY_MIS, STRATEGY_MIS_OPTIMAL: {}
        default: {
            _ = unknown_tag();
        }
    }
    switch p.heuristic {
        case HEURISTIC_BALANCE, HEURISTIC_POWER: {}
        default: {
            _ = unknown_tag();
        }
    }
    switch p.light_sampling {
        case LIGHT_SAMPLING_AREA, LIGHT_SAMPLING_SOLID_ANGLE, LIGHT_SAMPLING_SOLID_ANGLE_COSINE,
            LIGHT_SAMPLING_ADAPTIVE, LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE: {}
        default: {
            _ = unknown_tag();
        }
    }
}

@group(0) @binding(0) var<uniform> params: Params;
// #if USE_CWBVH
@group(0) @binding(1) var<storage, read> nodes: array<BvhNode>;
// #endif
// The BVH2 alternative shares the binding with its own layout (`gpu/bvh2.wgsl`).
// #if USE_BVH2
@group(0) @binding(1) var<storage, read> nodes: array<vec4<u32>>;
// #endif
@group(0) @binding(2) var<storage, read> prims: array<Prim>;
@group(0) @binding(3) var<storage, read> materials: array<Material>;
@group(0) @binding(4) var<storage, read> lights: array<Light>;
// Polygon lights' triangles (`lights/mod.wgsl`), then the mesh vertex attributes at `params.attr`
// (`geometry/mesh_attributes.wgsl`), then the texture records at `params.textures` (`textures/mod.wgsl`): one
// buffer, as the path tracer already binds the 8 storage buffers wgpu's portable limits allow per
// stage.
@group(0) @binding(5) var<storage, read> vertex_data: array<vec4f>;
@group(0) @binding(6) var<storage, read> tables: array<f32>;
// Accumulation, three planes of width·height vec4: running mean, Welford's M2, mean of the
// even-numbered samples; then, for dispatches of several samples, one plane per sample of the
// dispatch holding its radiance until `fold` adds it in.
@group(0) @binding(7) var<storage, read_write> accum: array<vec4f>;
// [0] = samples that were not finite (counted as zero, like the CPU).
@group(0) @binding(8) var<storage, read_write> counters: array<atomic<u32>>;
// The environment map's texels (`lights/envmap.wgsl`), rgba32float read with textureLoad; the
// binding holds a 1×1 placeholder in scenes without a map, whose programs do not declare it.
// #if HAS_ENVMAP
@group(0) @binding(9) var envmap_texels: texture_2d<f32>;
// #endif
// The bitmaps' texels (`textures/mod.wgsl`), one rgba32float texture used as a linear array; a 1×1
// placeholder in scenes without bitmaps, whose programs do not declare it unless textured.
// #if HAS_TEXTURES
@group(0) @binding(10) var texture_texels: texture_2d<f32>;
// #endif
