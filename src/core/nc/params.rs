//! Where a program's parameters live: numbered parameters (`#1`…), named ones
//! (`#<depth>` local to a subroutine, `#<_depth>` global), and the call levels that give
//! each subroutine call its own local parameters.
//!
//! The two controls differ, and the store follows the dialect:
//! - LinuxCNC: `#1`–`#30` are local to a call level; an unset numbered parameter reads 0;
//!   an unset named one is an error.
//! - Fanuc Custom Macro B: `#1`–`#33` are local to a macro call level (G65; M98 shares
//!   its caller's), `#100`… are common; an unset variable is *vacant* (`#0` always is).
//!
//! System parameters that describe the machine's state (positions, modal codes) are
//! answered by the interpreter (`system.rs`), not stored here.

use std::collections::HashMap;

/// Local numbered parameters of one call level (LinuxCNC has 30, Fanuc 33).
pub(crate) const LINUXCNC_LOCALS: u32 = 30;
pub(crate) const FANUC_LOCALS: u32 = 33;

/// Parameters of one call level.
#[derive(Debug, Clone, Default)]
struct Level {
    numbered: Vec<Option<f64>>,
    named: HashMap<String, f64>,
}

/// The parameter store.
#[derive(Debug, Clone)]
pub(crate) struct ParamStore {
    global: HashMap<u32, f64>,
    globals_named: HashMap<String, f64>,
    levels: Vec<Level>,
    locals: u32,
    /// An unset numbered parameter reads as 0 (LinuxCNC) rather than vacant (Fanuc).
    unset_is_zero: bool,
}

impl ParamStore {
    /// A store for LinuxCNC (`fanuc` false) or Fanuc programs.
    pub fn new(fanuc: bool) -> Self {
        let locals = if fanuc { FANUC_LOCALS } else { LINUXCNC_LOCALS };
        ParamStore {
            global: HashMap::new(),
            globals_named: HashMap::new(),
            levels: vec![Level { numbered: vec![None; locals as usize], ..Level::default() }],
            locals,
            unset_is_zero: !fanuc,
        }
    }

    /// Follows Fanuc's rules (`fanuc`) or LinuxCNC's; only before the program sets any.
    pub fn set_fanuc(&mut self, fanuc: bool) {
        *self = ParamStore::new(fanuc);
    }

    fn level(&self) -> &Level {
        self.levels.last().expect("the main level is never popped")
    }

    fn level_mut(&mut self) -> &mut Level {
        self.levels.last_mut().expect("the main level is never popped")
    }

    /// Reads numbered parameter `n` (`None`: vacant).
    pub fn get(&self, n: u32) -> Option<f64> {
        let value = match n {
            0 => None,
            n if n <= self.locals => self.level().numbered[n as usize - 1],
            n => self.global.get(&n).copied(),
        };
        value.or(if self.unset_is_zero && n > 0 { Some(0.0) } else { None })
    }

    /// Sets numbered parameter `n` (`None` makes it vacant).
    pub fn set(&mut self, n: u32, value: Option<f64>) -> Result<(), String> {
        if n == 0 {
            return Err("#0 is always vacant and cannot be set".to_string());
        }
        if n <= self.locals {
            self.level_mut().numbered[n as usize - 1] = value;
        } else {
            match value {
                Some(v) => {
                    self.global.insert(n, v);
                }
                None => {
                    self.global.remove(&n);
                }
            }
        }
        Ok(())
    }

    /// Reads named parameter `name` (upper case): `_`-names are global, others belong to
    /// the call level.
    pub fn named(&self, name: &str) -> Option<f64> {
        if name.starts_with('_') {
            self.globals_named.get(name).copied()
        } else {
            self.level().named.get(name).copied()
        }
    }

    /// Sets named parameter `name`.
    pub fn set_named(&mut self, name: &str, value: f64) {
        if name.starts_with('_') {
            self.globals_named.insert(name.to_string(), value);
        } else {
            self.level_mut().named.insert(name.to_string(), value);
        }
    }

    /// Opens a call level whose first local parameters are `args` (`#1`, `#2`, …; a
    /// `None` stays vacant).
    pub fn push_level(&mut self, args: &[(u32, Option<f64>)]) {
        let mut level = Level { numbered: vec![None; self.locals as usize], ..Level::default() };
        for &(n, v) in args {
            if (1..=self.locals).contains(&n) {
                level.numbered[n as usize - 1] = v;
            }
        }
        self.levels.push(level);
    }

    /// Closes the innermost call level.
    pub fn pop_level(&mut self) {
        if self.levels.len() > 1 {
            self.levels.pop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linuxcnc_locals_belong_to_their_call_level_and_unset_ones_read_zero() {
        let mut p = ParamStore::new(false);
        p.set(1, Some(5.0)).unwrap();
        p.set(100, Some(7.0)).unwrap();
        p.push_level(&[(1, Some(2.0))]);
        assert_eq!(p.get(1), Some(2.0));
        assert_eq!(p.get(2), Some(0.0));
        assert_eq!(p.get(100), Some(7.0));
        p.set_named("DEPTH", 3.0);
        p.set_named("_GLOBAL", 4.0);
        p.pop_level();
        assert_eq!(p.get(1), Some(5.0));
        assert_eq!(p.named("DEPTH"), None);
        assert_eq!(p.named("_GLOBAL"), Some(4.0));
    }

    #[test]
    fn fanuc_variables_are_vacant_until_set_and_hash_zero_cannot_be_set() {
        let mut p = ParamStore::new(true);
        assert_eq!(p.get(33), None);
        assert_eq!(p.get(500), None);
        p.set(500, Some(1.5)).unwrap();
        assert_eq!(p.get(500), Some(1.5));
        p.set(500, None).unwrap();
        assert_eq!(p.get(500), None);
        assert!(p.set(0, Some(1.0)).is_err());
    }
}
