// The camera's primary ray, the twin of `camera.rs` (`Camera::sample_ray`), from the camera
// fields of the per-dispatch parameters (`Params`): the projection's CAMERA_* tag, the frame,
// the film's half-extents in cam_origin.w and cam_forward.w, and the thin lens's aperture radius
// and focus distance in cam_right.w and cam_up.w. An unknown tag flags the sample.

// `Camera::sample_ray` from the film position `film` (pixels): the thin lens draws its lens
// point after the film position, the other projections draw nothing.
fn camera_ray(film: vec2f) -> Ray {
    // The principal point offset in pixels (`Camera::screen`; adding 0 is exact).
    let p = film + params.cam_shift.xy;
    let sx = 2.0 * p.x / f32(params.width) - 1.0;
    let sy = 1.0 - 2.0 * p.y / f32(params.height);
    let along_x = (sx * params.cam_origin.w) * params.cam_right.xyz;
    let along_y = (sy * params.cam_forward.w) * params.cam_up.xyz;
    switch params.camera {
        case CAMERA_PERSPECTIVE: {
            return Ray(params.cam_origin.xyz, normalize_glam(params.cam_forward.xyz + along_x + along_y), inf());
        }
        case CAMERA_THIN_LENS: {
            // `Camera::lens_ray`: through the chief ray's point on the plane of focus.
            let focus = (params.cam_forward.xyz + along_x + along_y) * params.cam_up.w;
            let l = params.cam_right.w * sample_uniform_disk_concentric(sampler_lens_2d());
            let on_lens = l.x * params.cam_right.xyz + l.y * params.cam_up.xyz;
            return Ray(params.cam_origin.xyz + on_lens, normalize_glam(focus - on_lens), inf());
        }
        case CAMERA_ORTHOGRAPHIC: {
            return Ray(params.cam_origin.xyz + along_x + along_y, params.cam_forward.xyz, inf());
        }
        default: {
            let nan = unknown_tag();
            return Ray(vec3f(nan), vec3f(nan), inf());
        }
    }
}
