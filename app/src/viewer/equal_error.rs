//! Equal-error comparison: lanes take turns by render time and each stops when its relMSE
//! (against the reference, or the half-buffer estimate without one) reaches the target; the
//! render times to that error are the comparison, the inverse ratio of the strategies'
//! efficiencies.

use super::prediction::MIN_SPP;
use super::worker::LaneView;

/// Whether `lane` has reached relMSE `target`, and at what render time and spp. Not before
/// [`MIN_SPP`] samples: a half-buffer estimate from two or three samples can fall below any
/// target by chance.
pub fn reached(lane: &LaneView, target: f64) -> Option<(f64, u32)> {
    let (e, _) = lane.error?;
    (lane.spp >= MIN_SPP && e <= target).then_some((lane.render_seconds, lane.spp))
}

/// The equal-error report: one line per lane, its time and spp to the target and how many
/// times the fastest lane's time that is, or its current error while it still runs.
pub fn report(lanes: &[LaneView], target: f64) -> Vec<String> {
    let fastest = lanes
        .iter()
        .filter_map(|l| l.reached.map(|(t, _)| t))
        .fold(f64::INFINITY, f64::min);
    lanes
        .iter()
        .map(|l| match l.reached {
            Some((t, spp)) => format!(
                "{}: relMSE {target:.0e} in {t:.2} s, {spp} spp ({:.2}× the fastest)",
                l.label,
                t / fastest
            ),
            None => format!(
                "{}: running, relMSE {} after {:.2} s",
                l.label,
                l.error.map_or("–".into(), |(e, _)| format!("{e:.2e}")),
                l.render_seconds
            ),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::convergence::ErrorSource;

    fn lane(label: &str, spp: u32, seconds: f64, error: Option<f64>) -> LaneView {
        LaneView {
            spp,
            render_seconds: seconds,
            error: error.map(|e| (e, ErrorSource::Reference)),
            ..crate::viewer::worker::empty_lane_view(label)
        }
    }

    #[test]
    fn a_lane_reaches_the_target_at_its_error_not_before_min_spp() {
        assert_eq!(
            reached(&lane("a", 8, 2.0, Some(0.009)), 0.01),
            Some((2.0, 8))
        );
        assert_eq!(reached(&lane("a", 8, 2.0, Some(0.011)), 0.01), None);
        assert_eq!(reached(&lane("a", 2, 2.0, Some(1e-9)), 0.01), None);
        assert_eq!(reached(&lane("a", 8, 2.0, None), 0.01), None);
    }

    #[test]
    fn report_gives_times_relative_to_the_fastest() {
        let mut a = lane("light", 800, 12.0, Some(0.01));
        a.reached = Some((12.0, 800));
        let mut b = lane("mis", 200, 3.0, Some(0.01));
        b.reached = Some((3.0, 200));
        let c = lane("bsdf", 50, 3.5, Some(0.2));
        let r = report(&[a, b, c], 0.01);
        assert_eq!(
            r[0],
            "light: relMSE 1e-2 in 12.00 s, 800 spp (4.00× the fastest)"
        );
        assert_eq!(
            r[1],
            "mis: relMSE 1e-2 in 3.00 s, 200 spp (1.00× the fastest)"
        );
        assert_eq!(r[2], "bsdf: running, relMSE 2.00e-1 after 3.50 s");
    }
}
