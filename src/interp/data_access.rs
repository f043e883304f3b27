//! Module data by name, for services outside the program (Robot Web Services through the
//! controller): list a task's data symbols with their values as RAPID text, and write a
//! `VAR` or `PERS` from RAPID literal text with the same shape check `--pers` files get.
//! Only the program's own modules are visible (the embedded stdlib is not).

use super::Interp;
use super::pers;
use super::value::Value;
use crate::ast::Storage;
use crate::ir::GlobalOrigin;

/// One data symbol of the program's own modules.
#[derive(Clone, Debug, PartialEq)]
pub struct DataSymbol {
    /// Index in the program's globals (for [`Interp::set_data_text`]).
    pub index: usize,
    /// Module name as written.
    pub module: String,
    /// Data name as declared.
    pub name: String,
    /// `VAR`, `PERS` or `CONST`.
    pub storage: Storage,
    /// Type name as RAPID writes it.
    pub data_type: String,
    /// Array sizes (empty for a scalar).
    pub dims: Vec<u32>,
    /// The current value as RAPID literal text.
    pub value: String,
}

/// Why a write was refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DataWriteError {
    /// No such data in the program's modules.
    Unknown,
    /// A constant cannot be written.
    Constant(String),
    /// The text is no RAPID literal of the data's type and size.
    BadValue(String),
}

impl Interp {
    /// The data symbols of the program's own modules, optionally only those of `module`
    /// and/or named `name` (both case-insensitive), in declaration order.
    pub fn data_symbols(&self, module: Option<&str>, name: Option<&str>) -> Vec<DataSymbol> {
        let prog = &self.prog;
        prog.globals
            .iter()
            .enumerate()
            .filter_map(|(i, g)| {
                let GlobalOrigin::Module(m) = g.origin else {
                    return None;
                };
                let info = prog.modules.get(m.0 as usize)?;
                if info.stdlib
                    || module.is_some_and(|w| !w.eq_ignore_ascii_case(&info.name))
                    || name.is_some_and(|w| !w.eq_ignore_ascii_case(&g.name))
                {
                    return None;
                }
                let value = self.globals.get(i).map(pers::to_text).unwrap_or_default();
                Some(DataSymbol {
                    index: i,
                    module: info.name.clone(),
                    name: g.name.clone(),
                    storage: g.storage,
                    data_type: prog.types.name(g.ty.base).to_string(),
                    dims: g.dims.clone(),
                    value,
                })
            })
            .collect()
    }

    /// The current value of the data symbol at `index` (from [`Interp::data_symbols`]).
    pub fn data_value(&self, index: usize) -> Option<&Value> {
        self.globals.get(index)
    }

    /// Write the data symbol at `index` (from [`Interp::data_symbols`]) from RAPID literal
    /// text (`42`, `[1,2,3]`, `"text"`, `TRUE`). The value must have the data's shape; a
    /// constant is refused.
    pub fn set_data_text(&mut self, index: usize, text: &str) -> Result<(), DataWriteError> {
        let g = self
            .prog
            .globals
            .get(index)
            .ok_or(DataWriteError::Unknown)?;
        if !matches!(g.origin, GlobalOrigin::Module(_)) {
            return Err(DataWriteError::Unknown);
        }
        if g.storage == Storage::Const {
            return Err(DataWriteError::Constant(g.name.clone()));
        }
        let ty = g.ty;
        let type_name = self.prog.types.name(ty.base).to_string();
        let name = g.name.clone();
        let bad = || {
            DataWriteError::BadValue(format!(
                "`{text}` is not a value of {type_name}{} {name}",
                pers::dims_text(&self.prog.globals[index].dims)
            ))
        };
        let lit = crate::functions::format::parse_value(text.trim()).ok_or_else(bad)?;
        let slot = self.globals.get(index).ok_or(DataWriteError::Unknown)?;
        let mut v: Value = slot.clone();
        if !pers::fill(&mut v, &lit) || !pers::fits(&self.prog.types, ty, &v) {
            return Err(bad());
        }
        if let Some(slot) = self.globals.get_mut(index) {
            *slot = v;
        }
        Ok(())
    }
}
