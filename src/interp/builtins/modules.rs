//! Program modules at run time: `ModExist`. Loading, unloading and saving modules while the
//! program runs (`Load`, `UnLoad`, `StartLoad`, …) are not supported yet; `rapidvc check`
//! names them, so `ModExist` answers for the modules the program was started with.

use super::Registry;
use crate::interp::value::Value;

/// Register this domain.
pub(super) fn register(r: &mut Registry) {
    // ABB: "ModExist is used to check whether a given module exists in the program task";
    // module names are compared without regard to case, as every RAPID name.
    r.add("FUNC bool ModExist(string ModuleName)", |cx| {
        let name = cx.str(0)?;
        let found =
            cx.p.modules
                .iter()
                .any(|m| m.name.eq_ignore_ascii_case(name));
        Ok(Value::Bool(found))
    });
}
