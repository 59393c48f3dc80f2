// Carlson's symmetric elliptic integrals R_F and R_J by one shared duplication loop, the twin of
// `sampling/elliptic.rs`: both of Carlson's stopping rules (CARLSON_RF_Q, CARLSON_RJ_Q), at most
// MAX_CARLSON_STEPS steps, then the fifth-order series about the arguments' means.

// R_C(1, 1 + e): the series near 0, atan(√e)/√e above, atanh(√−e)/√−e below.
fn carlson_rc1(e: f32) -> f32 {
    if abs(e) < 0.05 {
        return 1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0))));
    }
    if e > 0.0 {
        let s = sqrt(e);
        return atan2_precise(s, 1.0) / s;
    }
    let s = sqrt(-e);
    return 0.5 * log((1.0 + s) / (1.0 - s)) / s;
}

// `carlson_rf_rj`: (R_F(x, y, z), R_J(x, y, z, p)).
fn carlson_rf_rj(x: f32, y: f32, z: f32, p: f32) -> vec2f {
    let af0 = (x + y + z) / 3.0;
    let aj0 = (x + y + z + 2.0 * p) / 5.0;
    let qf = CARLSON_RF_Q * max(max(abs(af0 - x), abs(af0 - y)), abs(af0 - z));
    let qj = CARLSON_RJ_Q * max(max(abs(aj0 - x), abs(aj0 - y)), max(abs(aj0 - z), abs(aj0 - p)));
    let delta = (p - x) * (p - y) * (p - z);
    var xm = x;
    var ym = y;
    var zm = z;
    var pm = p;
    var af = af0;
    var aj = aj0;
    var scale = 1.0;
    var sum = 0.0;
    for (var i = 0u; i < MAX_CARLSON_STEPS; i++) {
        if scale * qf < abs(af) && scale * qj < abs(aj) {
            break;
        }
        let sx = sqrt(xm);
        let sy = sqrt(ym);
        let sz = sqrt(zm);
        let sp = sqrt(pm);
        let lambda = sx * (sy + sz) + sy * sz;
        let inv_d = 1.0 / ((sp + sx) * (sp + sy) * (sp + sz));
        let e = scale * scale * scale * delta * inv_d * inv_d;
        sum += scale * carlson_rc1(e) * inv_d;
        xm = 0.25 * (xm + lambda);
        ym = 0.25 * (ym + lambda);
        zm = 0.25 * (zm + lambda);
        pm = 0.25 * (pm + lambda);
        af = 0.25 * (af + lambda);
        aj = 0.25 * (aj + lambda);
        scale *= 0.25;
    }
    var k = scale / af;
    var dx = (af0 - x) * k;
    var dy = (af0 - y) * k;
    var dz = -(dx + dy);
    var e2 = dx * dy - dz * dz;
    var e3 = dx * dy * dz;
    let rf = (1.0 - e2 * (1.0 / 10.0) + e3 * (1.0 / 14.0) + e2 * e2 * (1.0 / 24.0)
        - e2 * e3 * (3.0 / 44.0)) / sqrt(af);
    k = scale / aj;
    dx = (aj0 - x) * k;
    dy = (aj0 - y) * k;
    dz = (aj0 - z) * k;
    let dp = -0.5 * (dx + dy + dz);
    let xyz = dx * dy * dz;
    e2 = dx * dy + dx * dz + dy * dz - 3.0 * dp * dp;
    e3 = xyz + 2.0 * e2 * dp + 4.0 * dp * dp * dp;
    let e4 = (2.0 * xyz + e2 * dp + 3.0 * dp * dp * dp) * dp;
    let e5 = xyz * dp * dp;
    let series = 1.0 - e2 * (3.0 / 14.0) + e3 * (1.0 / 6.0) + e2 * e2 * (9.0 / 88.0)
        - e4 * (3.0 / 22.0) - e2 * e3 * (9.0 / 52.0) + e5 * (3.0 / 26.0);
    let rj = scale * series / (aj * sqrt(aj)) + 6.0 * sum;
    return vec2f(rf, rj);
}
