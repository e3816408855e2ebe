//! What a part of a generated program does: the step of the process (seed 004 Table 1;
//! MODEL.md §8), the layer and the height it cuts, and the region it treats. Planners put a
//! [`Section`] event before each part of the paths they assemble; the NC writer turns each
//! into a comment (`(LAYER 2 Z-20 TROCHOIDAL GROOVING REGION 1)`), and the time and cost
//! break-downs count moves by it.

use serde::{Deserialize, Serialize};

/// A step of the process (seed 004 Table 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, utoipa::ToSchema)]
#[serde(rename_all = "snake_case")]
pub enum Step {
    /// The approach holes: helical entries and the full circle at their bottom (step 1).
    HelicalBoring,
    /// Spiral expansion of a round region from its approach hole (step 2).
    SpiralHoleExpansion,
    /// Trochoid cycles along the critical stretches of the medial axis (step 3).
    TrochoidalGrooving,
    /// Class C stretches cut in passes of a small axial depth (seed 004 §2.3).
    ZCutDivision,
    /// Contour-parallel rough side cutting (step 4).
    RoughSideCutting,
    /// Contour-parallel intermediate-rough side cutting of the last layer (step 9).
    IntermediateRoughSideCutting,
    /// The conventional strategy the papers compare with: a ball end mill in thin
    /// contour-parallel levels (seed 004 §3.3).
    ConventionalBallRoughing,
    /// Intermediate roughing of the stair steps the layers' roughing leaves on a sloped
    /// wall or floor, with a ball or radius end mill in thin z levels (issue 32, seed 004
    /// case II's slanted bottom).
    StairStepRoughing,
}

impl Step {
    /// The step's name in words, lower case (`"trochoidal grooving"`).
    pub fn name(self) -> &'static str {
        match self {
            Step::HelicalBoring => "helical boring",
            Step::SpiralHoleExpansion => "spiral hole expansion",
            Step::TrochoidalGrooving => "trochoidal grooving",
            Step::ZCutDivision => "z-cut division",
            Step::RoughSideCutting => "rough side cutting",
            Step::IntermediateRoughSideCutting => "intermediate-rough side cutting",
            Step::ConventionalBallRoughing => "conventional ball-end roughing",
            Step::StairStepRoughing => "stair-step intermediate roughing",
        }
    }
}

/// The label of a part of a program: every move from its event up to the next section
/// event belongs to it (the moves that lead to the part, over the safe height, included).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// The layer, counted from 0 at the top as the job's result counts them (comments count
    /// from 1).
    pub layer: u32,
    /// The height this part cuts at (the bottom of its level), mm.
    pub z_mm: f64,
    pub step: Step,
    /// The region treated: the index of its treatment in the plan (comments count from 1);
    /// `None` for the contour-parallel path, which covers the whole layer.
    pub region: Option<u32>,
}

impl Section {
    /// Whether `other` starts a new part after this one: another layer, height, step or
    /// region.
    pub fn differs_from(&self, other: &Section) -> bool {
        self.layer != other.layer
            || self.step != other.step
            || self.region != other.region
            || (self.z_mm - other.z_mm).abs() > SAME_SECTION_Z_MM
    }
}

/// Heights of two sections closer than this are the same level, mm (well below any written
/// resolution).
const SAME_SECTION_Z_MM: f64 = 1e-9;

/// The section events of `labels` (one label per move, `None` for moves outside any part):
/// one before each move whose label differs from the one before it. Each event carries the
/// 1-based line of the move it precedes.
pub fn section_events(labels: &[Option<Section>]) -> Vec<super::Event> {
    let mut events = Vec::new();
    let mut current: Option<Section> = None;
    for (i, label) in labels.iter().enumerate() {
        let Some(label) = label else { continue };
        if current.is_none_or(|c| c.differs_from(label)) {
            let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
            events.push(super::Event { kind: super::EventKind::Section(*label), before_move: i, line });
            current = Some(*label);
        }
    }
    events
}

/// The label of every one of `moves` moves from the section events among `events`: each
/// move gets the last section that starts at or before it (`None` before the first).
pub fn labels_of(events: &[super::Event], moves: usize) -> Vec<Option<Section>> {
    let mut starts: Vec<(usize, Section)> = events
        .iter()
        .filter_map(|e| match e.kind {
            super::EventKind::Section(s) => Some((e.before_move, s)),
            _ => None,
        })
        .collect();
    starts.sort_by_key(|(at, _)| *at);
    let mut labels = vec![None; moves];
    let mut next = starts.iter().peekable();
    let mut current = None;
    for (i, label) in labels.iter_mut().enumerate() {
        while let Some((_, s)) = next.next_if(|(at, _)| *at <= i) {
            current = Some(*s);
        }
        *label = current;
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::toolpath::EventKind;

    fn section(layer: u32, z_mm: f64, step: Step, region: Option<u32>) -> Section {
        Section { layer, z_mm, step, region }
    }

    #[test]
    fn a_section_event_starts_each_run_of_equal_labels_and_the_labels_come_back_from_the_events() {
        let a = section(0, -10.0, Step::HelicalBoring, Some(0));
        let b = section(0, -10.0, Step::TrochoidalGrooving, Some(0));
        let c = section(1, -20.0, Step::HelicalBoring, Some(0));
        let labels = vec![None, Some(a), Some(a), Some(b), Some(b), Some(c)];
        let events = section_events(&labels);
        let starts: Vec<(usize, u32)> = events.iter().map(|e| (e.before_move, e.line)).collect();
        assert_eq!(starts, [(1, 2), (3, 4), (5, 6)]);
        assert!(events.iter().all(|e| matches!(e.kind, EventKind::Section(_))));
        assert_eq!(labels_of(&events, labels.len()), labels);
    }

    #[test]
    fn sections_differ_by_layer_height_step_or_region() {
        let a = section(1, -20.0, Step::TrochoidalGrooving, Some(2));
        assert!(!a.differs_from(&a));
        for other in [
            section(2, -20.0, Step::TrochoidalGrooving, Some(2)),
            section(1, -17.5, Step::TrochoidalGrooving, Some(2)),
            section(1, -20.0, Step::HelicalBoring, Some(2)),
            section(1, -20.0, Step::TrochoidalGrooving, None),
        ] {
            assert!(a.differs_from(&other), "{other:?}");
        }
    }

    #[test]
    fn steps_serialise_as_snake_case_and_have_names_in_words() {
        assert_eq!(serde_json::to_string(&Step::ZCutDivision).unwrap(), "\"z_cut_division\"");
        assert_eq!(Step::IntermediateRoughSideCutting.name(), "intermediate-rough side cutting");
    }
}
