//! Parity of the WGSL samplers with `lumis::sampler` (issue 19): `sampler/mod.wgsl` (the closed
//! `switch` on the sampler tag and the named dimensions), `sampler/zsobol.wgsl`, `sampler/sobol.wgsl`,
//! `sampler/owen.wgsl`, `sampler/morton.wgsl` and `gpu/u64.wgsl` against their Rust twins, **bit for bit** (integer
//! arithmetic and exact conversions only: any difference is a bug, so no tolerance).
//!
//! Inputs, for both samplers, every combination of: seeds 0, 1, 19, 0xdead_beef and 8 random
//! ones; pixels at tile corners and edges ((0, 0), (63, 63), (64, 0), (0, 64), …), far out (up to
//! 65 535 and u32::MAX, where the tile goes into the key and the pixel index wraps) and 8 random
//! ones; samples 0…3, 4095/4096/4097 (the first epoch change), 8191/8192, 2^20 + 5, u32::MAX and
//! 8 random ones below 20 000; with bounces 0, 1, 2, 7, 1000, 2^29 (where `dim::at` wraps) or
//! random ones, and raw dimensions up to u32::MAX − 1, in rotation. Then 64 items per sampler
//! with every input random. The random inputs come from `Rng::new(19, …)`.
//!
//! Deliberate bugs tried (each in the WGSL only: the test run, the change undone; counts from
//! `every_dimension_matches_the_cpu_bit_for_bit`, 4624 items per sampler, 3424 of the sobol ones
//! at samples ≥ 4096 and 3712 outside the first 64×64 tile; the independent sampler's draws and
//! the building blocks agreed every time):
//! * `sampler_light_2d` drawing `DIM_CAMERA` (the `sampler:light_camera` mutant's bug): failed,
//!   `light_2d.x` and `.y` differ on all 4624 sobol items, nothing else does;
//! * the Owen scramble left out of `zsobol_get_1d` (`unit_f32(sobol_0(i))`): failed, every 1-D
//!   draw (mixture, light selection, lobe, RR, `get_1d`) differs on all 4624 items, the 2-D
//!   draws agree;
//! * the epoch left out of the key (`sample >> ZSOBOL_EPOCH_LOG2` replaced by 0): failed, all 13
//!   draws differ on exactly the 3424 items at samples ≥ 4096, so the epoch inputs are what
//!   catch it;
//! * the tile left out of the key (the tile hash replaced by that of tile (0, 0)): failed, all 13
//!   draws differ on exactly the 3712 items outside the first tile.
//!
//! Runs on any wgpu adapter (lavapipe where there is no GPU); `LUMIS_SKIP_GPU_TESTS=1` skips.

use crate::gpu_common;
use gpu_common::parity::any_scene_gpu;
use lumis::gpu::kernel::run_snippet;
use lumis::gpu::scene::SamplerTag;
use lumis::integrator::Settings;
use lumis::rng::Rng;
use lumis::sampler::owen::{hash3, hash32, mix64, owen_scramble};
use lumis::sampler::sobol::sobol_1;
use lumis::sampler::zsobol::permute_index;
use lumis::sampler::{Sampler, SamplerKind, morton::morton_encode};

fn bits(v: u32) -> f32 {
    f32::from_bits(v)
}

/// One sampler query: the sample, and the bounce and raw dimension asked for.
#[derive(Clone, Copy, Debug)]
struct Item {
    kind: SamplerKind,
    seed: u32,
    x: u32,
    y: u32,
    width: u32,
    sample: u32,
    bounce: u32,
    dim: u32,
}

/// The inputs described in the module doc, for both samplers.
fn items() -> Vec<Item> {
    let mut r = Rng::new(19, 0, 0);
    let mut u = move || r.next_u32();
    let mut seeds = vec![0u32, 1, 19, 0xdead_beef];
    let mut pixels = vec![
        (0u32, 0u32),
        (1, 0),
        (0, 1),
        (63, 63),
        (64, 0),
        (0, 64),
        (64, 64),
        (127, 65),
        (1000, 3),
        (65_535, 65_535),
        (u32::MAX, 7),
        (5, u32::MAX),
    ];
    let mut samples = vec![
        0u32,
        1,
        2,
        3,
        4095,
        4096,
        4097,
        8191,
        8192,
        (1 << 20) + 5,
        u32::MAX,
    ];
    let mut bounces = vec![0u32, 1, 2, 7, 1000, 1 << 29];
    for _ in 0..8 {
        seeds.push(u());
        pixels.push((u() % 4096, u() % 4096));
        samples.push(u() % 20_000);
        bounces.push(u() % 16);
    }
    let mut out = Vec::new();
    for kind in [SamplerKind::Independent, SamplerKind::Sobol] {
        for (i, &seed) in seeds.iter().enumerate() {
            for (j, &(x, y)) in pixels.iter().enumerate() {
                for (k, &sample) in samples.iter().enumerate() {
                    // Every (seed, pixel, sample) once; the bounce and dimension rotate.
                    let bounce = bounces[(i + j + k) % bounces.len()];
                    out.push(Item {
                        kind,
                        seed,
                        x,
                        y,
                        width: [640, 1, 4096, u32::MAX][(i + k) % 4],
                        sample,
                        bounce,
                        dim: [0, 1, 9, 17, 1 << 20, u32::MAX - 1, u() % 64][(j + k) % 7],
                    });
                }
            }
        }
    }
    // 64 fully random seeds on top, sobol and independent.
    for n in 0..128 {
        out.push(Item {
            kind: [SamplerKind::Independent, SamplerKind::Sobol][n % 2],
            seed: u(),
            x: u(),
            y: u(),
            width: u(),
            sample: u(),
            bounce: u() % 64,
            dim: u(),
        });
    }
    out
}

/// The names of the 13 values one item yields, in the order both sides draw them (the order
/// matters to the independent sampler, which ignores the dimensions).
const DRAWS: [&str; 13] = [
    "camera_2d.x",
    "camera_2d.y",
    "mixture_1d",
    "light_select_1d",
    "light_2d.x",
    "light_2d.y",
    "bsdf_lobe_1d",
    "bsdf_2d.x",
    "bsdf_2d.y",
    "rr_1d",
    "get_1d",
    "get_2d.x",
    "get_2d.y",
];

/// What the CPU's sampler draws for `it`, in [`DRAWS`] order.
fn cpu_draws(it: &Item) -> [f32; 13] {
    let mut s = Sampler::new(it.kind, it.seed, it.x, it.y, it.width, it.sample);
    let b = it.bounce;
    let c = s.camera_2d();
    let m = s.mixture_1d(b);
    let ls = s.light_select_1d(b);
    let l = s.light_2d(b);
    let lobe = s.bsdf_lobe_1d(b);
    let bs = s.bsdf_2d(b);
    let rr = s.rr_1d(b);
    let g1 = s.get_1d(it.dim);
    let g2 = s.get_2d(it.dim);
    [
        c.x, c.y, m, ls, l.x, l.y, lobe, bs.x, bs.y, rr, g1, g2.x, g2.y,
    ]
}

/// The same through `sampler/mod.wgsl`; the 14th value is 1 where the sample was flagged.
const DRAW_SNIPPET: &str =
    "let a = bitcast<vec4<u32>>(inp(0u)); let b = bitcast<vec4<u32>>(inp(1u));
     sampler_init(a.x, a.y, a.z, a.w, b.x, b.y);
     let c = sampler_camera_2d();
     let m = sampler_mixture_1d(b.z);
     let ls = sampler_light_select_1d(b.z);
     let l = sampler_light_2d(b.z);
     let lobe = sampler_bsdf_lobe_1d(b.z);
     let bs = sampler_bsdf_2d(b.z);
     let rr = sampler_rr_1d(b.z);
     let g1 = sampler_get_1d(b.w);
     let g2 = sampler_get_2d(b.w);
     outp(0u, vec4f(c, m, ls));
     outp(1u, vec4f(l, lobe, bs.x));
     outp(2u, vec4f(bs.y, rr, g1, g2.x));
     outp(3u, vec4f(g2.y, select(0.0, 1.0, unknown_tag_seen), 0.0, 0.0));";

fn tag(kind: SamplerKind) -> u32 {
    SamplerTag::of(kind).gpu_tag()
}

/// Every named dimension (and the raw `get_1d`/`get_2d` at an arbitrary dimension) of both
/// samplers, bit for bit, on the inputs of the module doc.
#[test]
fn every_dimension_matches_the_cpu_bit_for_bit() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let items = items();
    let mut inputs = Vec::new();
    for it in &items {
        inputs.push([bits(tag(it.kind)), bits(it.seed), bits(it.x), bits(it.y)]);
        inputs.push([
            bits(it.width),
            bits(it.sample),
            bits(it.bounce),
            bits(it.dim),
        ]);
    }
    let out = run_snippet(&gpu, &Settings::default(), DRAW_SNIPPET, &inputs, 2, 4)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut wrong = [[0usize; 13]; 2];
    let mut epoch_items = 0;
    let mut outside_first_tile = 0;
    let mut examples = Vec::new();
    for (it, o) in items.iter().zip(out.chunks(4)) {
        let got: Vec<f32> = o.iter().flatten().copied().collect();
        assert_eq!(got[13], 0.0, "{it:?}: flagged as an unknown tag");
        let sobol = it.kind == SamplerKind::Sobol;
        epoch_items += usize::from(sobol && it.sample >= 4096);
        outside_first_tile += usize::from(sobol && (it.x >= 64 || it.y >= 64));
        for (d, want) in cpu_draws(it).into_iter().enumerate() {
            if got[d].to_bits() != want.to_bits() {
                wrong[it.kind as usize][d] += 1;
                if examples.len() < 8 {
                    examples.push(format!("{it:?} {}: gpu {} cpu {want}", DRAWS[d], got[d]));
                }
            }
        }
    }
    let n = items.len() / 2;
    eprintln!(
        "{} items per sampler x {} draws ({epoch_items} sobol items at sample >= 4096, \
         {outside_first_tile} outside the first tile)",
        n,
        DRAWS.len()
    );
    for (k, name) in ["independent", "sobol"].iter().enumerate() {
        let summary: Vec<String> = DRAWS
            .iter()
            .zip(wrong[k])
            .filter(|(_, w)| *w > 0)
            .map(|(d, w)| format!("{d} {w}"))
            .collect();
        eprintln!("{name}: differing draws: {summary:?}");
    }
    assert!(
        wrong.iter().flatten().all(|&w| w == 0),
        "draws differ from the CPU's:\n{}",
        examples.join("\n")
    );
}

/// The building blocks on random 32-bit inputs (seed 19), bit for bit: `mix64`, `hash3`, `hash32`,
/// `owen_scramble`, `sobol_1` (inputs with each single bit set reach every column),
/// `morton_encode` and `permute_index` over 12 base-4 digits. A failure here says which block is
/// wrong where the draws above say only which dimension.
#[test]
fn building_blocks_match_bit_for_bit() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let mut r = Rng::new(19, 1, 0);
    let mut inputs: Vec<[f32; 4]> = Vec::new();
    let mut words = Vec::new();
    for i in 0..4096u32 {
        // Some inputs with few or all bits set, the rest random.
        let w: [u32; 4] = match i {
            0 => [0; 4],
            1 => [u32::MAX; 4],
            2..=33 => [1 << (i - 2), 1 << (i - 2), !(1 << (i - 2)), i],
            _ => std::array::from_fn(|_| r.next_u32()),
        };
        inputs.push(w.map(bits));
        words.push(w);
    }
    let out = run_snippet(
        &gpu,
        &Settings::default(),
        "let a = bitcast<vec4<u32>>(inp(0u));
         let m = mix64(a.xy);
         outp(0u, bitcast<vec4f>(vec4<u32>(m, hash3(a.x, a.y, a.zw), owen_scramble(a.x, a.y))));
         outp(1u, bitcast<vec4f>(vec4<u32>(sobol_1(a.x), morton_encode(a.x, a.y),
             permute_index(a.x & 0xffffffu, 12u, a.z), hash32(a.w))));",
        &inputs,
        1,
        2,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let names = [
        "mix64.lo",
        "mix64.hi",
        "hash3",
        "owen_scramble",
        "sobol_1",
        "morton_encode",
        "permute_index",
        "hash32",
    ];
    let mut wrong = [0usize; 8];
    let mut examples = Vec::new();
    for (w, o) in words.iter().zip(out.chunks(2)) {
        let key = (w[3] as u64) << 32 | w[2] as u64;
        let m = mix64((w[1] as u64) << 32 | w[0] as u64);
        let want = [
            m as u32,
            (m >> 32) as u32,
            hash3(w[0], w[1], key),
            owen_scramble(w[0], w[1]),
            sobol_1(w[0]),
            morton_encode(w[0], w[1]),
            permute_index(w[0] & 0xff_ffff, 12, w[2]),
            hash32(w[3]),
        ];
        let got: Vec<u32> = o.iter().flatten().map(|v| v.to_bits()).collect();
        for k in 0..8 {
            if got[k] != want[k] {
                wrong[k] += 1;
                if examples.len() < 8 {
                    examples.push(format!(
                        "{}({w:x?}): gpu {:#x} cpu {:#x}",
                        names[k], got[k], want[k]
                    ));
                }
            }
        }
    }
    eprintln!(
        "{} inputs; differing: {:?}",
        words.len(),
        names.iter().zip(wrong).collect::<Vec<_>>()
    );
    assert!(wrong.iter().all(|&w| w == 0), "{}", examples.join("\n"));
}

/// A sampler tag `SamplerKind` has no variant for fails loudly: the sample is flagged (the render
/// kernel then counts it non-finite) and every draw is NaN, instead of silently drawing zeros.
#[test]
fn an_unknown_sampler_tag_is_flagged() {
    let Some(gpu) = any_scene_gpu() else {
        return;
    };
    let bad = SamplerTag::ALL.len() as u32;
    let inputs = [
        [bits(bad), bits(1), bits(2), bits(3)],
        [bits(8), bits(0), bits(0), bits(0)],
    ];
    let out = run_snippet(&gpu, &Settings::default(), DRAW_SNIPPET, &inputs, 2, 4)
        .unwrap_or_else(|e| panic!("{e}"));
    let got: Vec<f32> = out.iter().flatten().copied().collect();
    assert_eq!(got[13], 1.0, "not flagged: {got:?}");
    assert!(got[..13].iter().all(|v| v.is_nan()), "{got:?}");
}
