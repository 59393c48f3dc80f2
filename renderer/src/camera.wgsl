// The pinhole camera's primary ray, the twin of `camera.rs` (`Camera::ray`), from the camera
// fields of the per-dispatch parameters (`Params`).

fn camera_ray(x: f32, y: f32) -> Ray {
    let sx = 2.0 * x / f32(params.width) - 1.0;
    let sy = 1.0 - 2.0 * y / f32(params.height);
    let d = params.cam_forward.xyz + (sx * params.cam_origin.w) * params.cam_right.xyz
        + (sy * params.cam_forward.w) * params.cam_up.xyz;
    return Ray(params.cam_origin.xyz, normalize_glam(d), inf());
}
