//! Reports of a slider on a beam (`slider_on_beam`) passing an end of its guide: the first
//! accepted state at which a slider corner lies past an end of the beam face, and the first at
//! which all four do (the slider has left the guide). The contact itself stays continuous there
//! (clr-contact clips the slider outline at the end); these notes tell the user it happened.

use crate::beam_face::GuideBeam;
use crate::clearance::ClearanceKind;
use crate::system::Model;

/// What one slider-on-beam element has reported so far.
#[derive(Debug, Clone, Copy, Default)]
struct Exit {
    /// First time a corner lay past an end: (t in s, corners past as a bit set, end arc in m).
    first: Option<(f64, u8, f64)>,
    /// First time all four corners lay past an end, s.
    all: Option<f64>,
}

/// The exits of every clearance element of a run (only slider-on-beam elements report).
#[derive(Debug, Clone, Default)]
pub(crate) struct GuideExits {
    exits: Vec<Exit>,
}

impl GuideExits {
    /// Nothing reported yet for the elements of `model`.
    pub(crate) fn new(model: &Model) -> Self {
        Self {
            exits: vec![Exit::default(); model.clearances.len()],
        }
    }

    /// Look at the detectors at the accepted state of time `t` (s), as the last contact commit
    /// left them. Allocates nothing.
    pub(crate) fn observe(&mut self, model: &Model, t: f64) {
        for (cl, exit) in model.clearances.iter().zip(&mut self.exits) {
            let ClearanceKind::FlexGuide(g) = &cl.kind else {
                continue;
            };
            if exit.all.is_some() {
                continue;
            }
            let det = &g.detector;
            let past = (0..4).fold(0u8, |m, k| m | (u8::from(det.past_end(k)) << k));
            if past == 0 {
                continue;
            }
            if exit.first.is_none() {
                let corner = past.trailing_zeros() as usize;
                let end = det.projection(corner).map_or(f64::NAN, |p| p.0);
                exit.first = Some((t, past, end));
            }
            if past == 0b1111 {
                exit.all = Some(t);
            }
        }
    }

    /// The notes of the run, one or two per element that passed an end of its guide.
    pub(crate) fn notes(&self, model: &Model) -> Vec<String> {
        let mut notes = Vec::new();
        for (cl, exit) in model.clearances.iter().zip(&self.exits) {
            let (ClearanceKind::FlexGuide(g), Some((t, past, end))) = (&cl.kind, exit.first) else {
                continue;
            };
            let beam = match g.beam {
                GuideBeam::Fixed(k) => &model.beams[k].name,
                GuideBeam::Floating(k) => &model.floating[k].name,
            };
            let which = if end > 0.0 { "end" } else { "start" };
            let corners: Vec<String> = (0..4)
                .filter(|k| past & (1 << k) != 0)
                .map(|k| format!("{k} ({})", CORNER_NAMES[k]))
                .collect();
            let (end, t) = (short(end), short(t));
            notes.push(format!(
                "slider `{}` (body `{}`) reached the {which} of its guide `{beam}` (s = {end} \
                 m) at t = {t} s: corner {} past it; the part of the slider past the end \
                 carries no contact force",
                cl.name,
                model.body_names.get(cl.j).map_or("?", String::as_str),
                corners.join(", "),
            ));
            if let Some(t_all) = exit.all {
                notes.push(format!(
                    "slider `{}` left its guide `{beam}` entirely (all four corners past the \
                     {which}, s = {end} m) at t = {} s",
                    cl.name,
                    short(t_all)
                ));
            }
        }
        notes
    }
}

/// `x` rounded to 9 significant digits (a beam length of 0.9999999999999999 m reads 1).
fn short(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(8 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

/// Corners 0..4 of a slider, counter-clockwise from (−L/2, −h/2) in the slider frame.
const CORNER_NAMES: [&str; 4] = ["bottom left", "bottom right", "top right", "top left"];
