//! Where a layer's overloads are in the written program (issue 29: "short spikes … are
//! reported with their lines"). A layer's verification names the moves of the layer's own
//! program; the plan's program joins every layer (copies moved down), splits moves where the
//! feed changes (each block keeps its source move as its `line`) and links them over the
//! safe height; the writer says which text line ends each move.

use super::report::ProcessPlan;

/// The first and last line of the written program (1-based) of each overload of each layer
/// report, in the order of `plan.layers` and of their `overloads`; `None` where the layer's
/// moves are not in the program. `move_lines` is the writer's line per program move
/// ([`crate::core::nc::WrittenProgram::move_lines`]).
pub fn overload_program_lines(plan: &ProcessPlan, move_lines: &[u32]) -> Vec<Vec<Option<(u32, u32)>>> {
    let program = &plan.evaluation.program;
    plan.layers
        .iter()
        .map(|layer| {
            layer
                .overloads
                .iter()
                .map(|o| {
                    let moves = program.moves.iter().zip(&plan.evaluation.move_layer).zip(move_lines);
                    o.written_lines(moves.filter(|((_, &owner), _)| owner == layer.index).map(|((m, _), &l)| (m, l)))
                })
                .collect()
        })
        .collect()
}
