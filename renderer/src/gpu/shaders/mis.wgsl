// Multiple-importance heuristics, the twin of `integrator/mis.rs`. `heuristic`: 0 balance, 1 power.

const HEURISTIC_BALANCE: u32 = 0u;
const HEURISTIC_POWER: u32 = 1u;

fn mis_weight(heuristic: u32, pa: f32, pb: f32) -> f32 {
    if !is_finite_f(pa) && !is_nan_f(pa) {
        return 1.0;
    }
    var a = pa;
    var b = pb;
    if heuristic == HEURISTIC_POWER {
        a = pa * pa;
        b = pb * pb;
    }
    let w = a / (a + b);
    if is_finite_f(w) {
        return w;
    } else if !is_finite_f(pb) && !is_nan_f(pb) {
        return 0.0;
    }
    let w2 = pa / (pa + pb);
    if is_finite_f(w2) {
        return w2;
    }
    return 0.0;
}
