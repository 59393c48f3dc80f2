//! The one wgpu error the viewer survives. GPU lanes render on the window's device from the render
//! thread, while eframe reconfigures the window's surface on the UI thread (on a resize, say).
//! wgpu-core waits for the queue to go idle before a configure and rejects it if work was
//! submitted meanwhile ("Failed to wait for GPU to come idle before reconfiguring the Surface").
//! That is a race, not a bug in the commands: the surface keeps its old configuration, and
//! egui-wgpu configures it again on the next frame that reports it suboptimal or outdated. So
//! that error is reported and passed over; every other error keeps wgpu's default, a panic.

use eframe::wgpu;
use std::sync::Arc;

/// What wgpu-core says when a submission slipped in during a surface configure's idle wait.
const CONFIGURE_RACE: &str = "Failed to wait for GPU to come idle before reconfiguring the Surface";

/// True for the error a surface configure gives when another thread submitted during its wait.
pub fn is_configure_race(error: &wgpu::Error) -> bool {
    matches!(error, wgpu::Error::Validation { description, .. } if description.contains(CONFIGURE_RACE))
}

/// Installs the handler on the window's device: a configure race is logged to stderr, any other
/// uncaptured error panics as wgpu's default handler does.
pub fn survive_configure_races(device: &wgpu::Device) {
    device.on_uncaptured_error(Arc::new(|error: wgpu::Error| {
        if is_configure_race(&error) {
            eprintln!(
                "lumis view: a surface configure raced a GPU render pass; retried next frame"
            );
            return;
        }
        panic!("wgpu error: {error}");
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn validation(description: &str) -> wgpu::Error {
        wgpu::Error::Validation {
            source: description.to_string().into(),
            description: description.to_string(),
        }
    }

    #[test]
    fn only_the_configure_race_is_survived() {
        // As wgpu 30 formats it.
        let race = "Validation Error\n\nCaused by:\n  In Surface::configure\n    \
                    Failed to wait for GPU to come idle before reconfiguring the Surface\n";
        assert!(is_configure_race(&validation(race)));
        assert!(!is_configure_race(&validation(
            "Validation Error\n\nCaused by:\n  In Device::create_bind_group\n    Buffer is invalid\n"
        )));
        assert!(!is_configure_race(&wgpu::Error::OutOfMemory {
            source: CONFIGURE_RACE.to_string().into()
        }));
    }
}
