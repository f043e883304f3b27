//! Corner paths at fly-by points: the end of the previous move and the start of the next are
//! superposed over a window inside the zone (the previous move ramps down while the next ramps
//! up), in Cartesian space between two linear/circular moves with the same tool, otherwise in
//! joint space.
//!
//! Staying inside the zone: the window contains only previous-move samples within the zone
//! radius of the fly-by point and next-move samples within the radius from it, and lies inside
//! both ramps. The remaining distance of the previous move shrinks convexly and the distance
//! the next one has covered grows convexly over the window, so their sum (which bounds the
//! distance from the fly-by point) never exceeds the radius.

use crate::robot::{JointsDeg, ToolData};

use super::super::limits;
use super::super::segment::{CornerSpan, Sample, Segment};
use super::Planner;
use super::path::superpose;

impl Planner {
    /// Build the corner path from the previous segment into `seg` for a zone of radius `zone`
    /// (mm, already halved). `ramp_up` is the number of `seg`'s samples in its ramp-up;
    /// `cartesian_tool` is set when `seg` is a Cartesian move with a robot-held tool.
    /// On success `seg.corner` is set (or left empty when the window is too small to matter);
    /// `Err` names why the corner could not be built (the fly-by point becomes a stop point).
    pub(super) fn build_corner(
        &self,
        seg: &mut Segment,
        zone: f64,
        ramp_up: usize,
        tool: &ToolData,
        cartesian_tool: Option<&ToolData>,
    ) -> Result<(), &'static str> {
        let Some(prev) = &self.prev else {
            return Ok(());
        };
        let (Some(a_end), false) = (prev.samples.last(), seg.samples.is_empty()) else {
            return Ok(());
        };
        let corner_point = a_end.tcp;
        let cp = corner_point.translation.vector;
        let w_a = prev
            .samples
            .iter()
            .rev()
            .take_while(|s| (s.tcp.translation.vector - cp).norm() <= zone)
            .count()
            .min(prev.samples.len().saturating_sub(prev.resume_at))
            .min(prev.ramp_down);
        let w_b = seg
            .samples
            .iter()
            .take_while(|s| (s.tcp.translation.vector - cp).norm() <= zone)
            .count()
            .min(ramp_up)
            .min(seg.samples.len().saturating_sub(1));
        let w = w_a.min(w_b);
        if w == 0 {
            return Ok(());
        }
        let enter = prev.samples.len() - w;
        let before = match enter.checked_sub(1) {
            Some(i) => prev.samples.get(i).map_or(prev.start, |s| s.q),
            None => prev.start,
        };
        let cartesian = match (prev.cartesian_tool.as_ref(), cartesian_tool) {
            (Some(a), Some(b)) => a == b,
            _ => false,
        };
        seg.corner_samples.clear();
        let mut last_q = before;
        let pairs = prev.samples.iter().skip(enter).zip(seg.samples.iter());
        for (a, b) in pairs {
            let sample = if cartesian {
                let tcp = superpose(&a.tcp, &b.tcp, &corner_point);
                let flange = tcp * tool.tframe.inverse();
                let q = self
                    .robot
                    .ik_nearest(&flange, &last_q)
                    .map_err(|_| "the corner path leaves the robot's reach")?;
                Sample { q, tcp }
            } else {
                let q = add_offset(&a.q, &b.q, &seg.start);
                self.robot
                    .check_limits(&q)
                    .map_err(|_| "the corner path leaves an axis range")?;
                Sample {
                    q,
                    tcp: self.robot.tcp_world(&q, tool),
                }
            };
            last_q = sample.q;
            seg.corner_samples.push(sample);
        }
        // Axis speeds over the corner and into the rest of the next move.
        let vmax = limits::axis_speeds(self.robot.model(), &self.settings);
        let (ratio, _, _) = limits::worst_speed_ratio(&before, &seg.corner_samples, self.dt, &vmax);
        let join = seg.samples.get(w).map_or(0.0, |s| {
            limits::step_speed_ratio(&last_q, &s.q, self.dt, &vmax).0
        });
        if ratio > 1.0 + limits::SPEED_SUPERVISION_SLACK
            || join > 1.0 + limits::SPEED_SUPERVISION_SLACK
        {
            seg.corner_samples.clear();
            return Err("an axis would exceed its speed limit in the corner path");
        }
        seg.corner = Some(CornerSpan {
            enter_at: enter,
            resume_at: w,
        });
        Ok(())
    }
}

/// `a + (b − origin)` per axis.
fn add_offset(a: &JointsDeg, b: &JointsDeg, origin: &JointsDeg) -> JointsDeg {
    let mut q = *a;
    for ((qi, bi), oi) in q.iter_mut().zip(b).zip(origin) {
        *qi += bi - oi;
    }
    q
}
