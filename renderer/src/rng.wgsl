// Counter-based random numbers, bit for bit the twin of `rng.rs`: PCG hash of (seed, pixel,
// sample) starts a PCG32 (RXS-M-XS) stream. u32 arithmetic wraps in WGSL as in Rust.

fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// One invocation renders one sample at a time, so the stream state is private.
var<private> rng_state: u32;

fn rng_init(seed: u32, pixel: u32, sample: u32) {
    rng_state = pcg_hash(seed ^ pcg_hash(pixel ^ pcg_hash(sample + 0x9e3779b9u)));
}

fn rng_next_u32() -> u32 {
    rng_state = rng_state * 747796405u + 2891336453u;
    let s = rng_state;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return (word >> 22u) ^ word;
}

// `unit_f32`: the top 24 of 32 random bits as k/2^24, exact, never 1 (the samplers' too).
fn unit_f32(bits: u32) -> f32 {
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}

// Uniform in [0, 1): 24 random bits, never 1.
fn rng_next_f32() -> f32 {
    return unit_f32(rng_next_u32());
}

fn rng_next_2d() -> vec2f {
    let x = rng_next_f32();
    return vec2f(x, rng_next_f32());
}
