// The GPU twin of `tonemap::srgb8`: reads the running mean straight from a GPU render's
// accumulation buffer and writes display pixels (exposure gain, clamp to [0, 1], the sRGB
// curve) into a texture that egui draws, so a GPU lane is shown without a readback.
// Kept in step with the Rust side by `gpu_display::tests`.

struct DisplayParams {
    width: u32,
    height: u32,
    gain: f32,
    _pad: u32,
}

@group(0) @binding(0) var<storage, read> mean: array<vec4<f32>>;
@group(0) @binding(1) var<uniform> params: DisplayParams;
@group(0) @binding(2) var target_image: texture_storage_2d<rgba8unorm, write>;

fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.0031308 {
        return 12.92 * x;
    }
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

// Non-finite values show as 0, as on the CPU side (x != x is NaN; a huge value is ±Inf).
fn display_channel(x: f32) -> f32 {
    let finite = x == x && abs(x) <= 3.4028235e38;
    return select(0.0, linear_to_srgb(clamp(x, 0.0, 1.0)), finite);
}

@compute @workgroup_size(8, 8, 1)
fn display_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let c = mean[id.y * params.width + id.x].rgb * params.gain;
    let rgb = vec3<f32>(display_channel(c.x), display_channel(c.y), display_channel(c.z));
    textureStore(target_image, vec2<i32>(id.xy), vec4<f32>(rgb, 1.0));
}
