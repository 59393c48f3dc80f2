// erfc, erf and erfinv in f32, the twin of `erf.rs`: the CPU's coefficients (f32 literals, each
// rounded once, as Rust rounds them) in the CPU's evaluation order.

// erfc(x) to a fractional error below 1.2e-7 (Numerical Recipes' `erfcc`).
fn erfc(x: f32) -> f32 {
    let z = abs(x);
    let t = 1.0 / (1.0 + 0.5 * z);
    let p = -1.2655122f
        + t * (1.0000237f
            + t * (0.37409196f
                + t * (0.09678418f
                    + t * (-0.18628806f
                        + t * (0.27886807f
                            + t * (-1.135204f
                                + t * (1.4885159f + t * (-0.82215223f + t * 0.17087277f))))))));
    let r = t * exp(-z * z + p);
    return select(2.0 - r, r, x >= 0.0);
}

fn erf(x: f32) -> f32 {
    return 1.0 - erfc(x);
}

// Giles 2010's single-precision inverse error function.
fn erfinv(x: f32) -> f32 {
    var w = -log((1.0 - x) * (1.0 + x));
    var p: f32;
    if w < 5.0 {
        w = w - 2.5;
        p = 2.8102264e-8f;
        p = 3.4327394e-7f + p * w;
        p = -3.5233877e-6f + p * w;
        p = -4.3915065e-6f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.001253725f + p * w;
        p = -0.0041776816f + p * w;
        p = 0.24664073f + p * w;
        p = 1.5014094f + p * w;
    } else {
        w = sqrt(w) - 3.0;
        p = -0.00020021426f;
        p = 0.00010095056f + p * w;
        p = 0.0013493432f + p * w;
        p = -0.0036734284f + p * w;
        p = 0.0057395077f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.0094388705f + p * w;
        p = 1.0016741f + p * w;
        p = 2.8329768f + p * w;
    }
    return p * x;
}
