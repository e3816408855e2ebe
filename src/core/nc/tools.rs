//! The tool table a program runs with: the request's entries, changed by the program's
//! own `G10` lines (LinuxCNC `G10 L1 P<tool> R<radius> Z<length>`; Fanuc `G10 L10/L11
//! P<H> R<length>` geometry and wear, `G10 L12/L13 P<D> R<radius>`).

use std::collections::HashMap;

use super::options::ToolEntry;

#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Entry {
    radius_mm: Option<f64>,
    length_mm: Option<f64>,
    radius_wear_mm: f64,
    length_wear_mm: f64,
}

/// Radii and lengths by tool, D or H number, mm.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct ToolTable {
    entries: HashMap<u32, Entry>,
}

impl ToolTable {
    pub fn new(entries: &[ToolEntry]) -> Self {
        let entries = entries
            .iter()
            .map(|e| (e.number, Entry { radius_mm: e.radius_mm, length_mm: e.length_mm, ..Entry::default() }))
            .collect();
        ToolTable { entries }
    }

    /// The radius of entry `n` (geometry plus wear), mm.
    pub fn radius_mm(&self, n: u32) -> Option<f64> {
        let e = self.entries.get(&n)?;
        e.radius_mm.map(|r| r + e.radius_wear_mm)
    }

    /// The length of entry `n` (geometry plus wear), mm.
    pub fn length_mm(&self, n: u32) -> Option<f64> {
        let e = self.entries.get(&n)?;
        e.length_mm.map(|l| l + e.length_wear_mm)
    }

    /// Sets the geometry radius (`wear` false) or the radius wear of entry `n`, mm.
    pub fn set_radius(&mut self, n: u32, value_mm: f64, wear: bool) {
        let e = self.entries.entry(n).or_default();
        if wear {
            e.radius_wear_mm = value_mm;
        } else {
            e.radius_mm = Some(value_mm);
        }
    }

    /// Sets the geometry length (`wear` false) or the length wear of entry `n`, mm.
    pub fn set_length(&mut self, n: u32, value_mm: f64, wear: bool) {
        let e = self.entries.entry(n).or_default();
        if wear {
            e.length_wear_mm = value_mm;
        } else {
            e.length_mm = Some(value_mm);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_program_can_set_geometry_and_wear_over_the_requests_entries() {
        let mut t = ToolTable::new(&[ToolEntry { number: 1, radius_mm: Some(5.0), length_mm: None }]);
        assert_eq!(t.radius_mm(1), Some(5.0));
        assert_eq!(t.length_mm(1), None);
        t.set_radius(1, -0.02, true);
        t.set_length(1, 120.0, false);
        assert!((t.radius_mm(1).unwrap() - 4.98).abs() < 1e-12);
        assert_eq!(t.length_mm(1), Some(120.0));
        assert_eq!(t.radius_mm(2), None);
    }
}
