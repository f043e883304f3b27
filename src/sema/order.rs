//! The order in which module data are initialised: each initial value after the data it
//! reads, with cycles reported.

use super::Checker;
use super::error::SemaErrorKind as K;
use crate::ir::GlobalId;

impl Checker<'_> {
    /// Globals with an initial value, dependencies first.
    pub(super) fn init_order(&mut self) -> Vec<GlobalId> {
        let n = self.globals.len();
        // 0 = unvisited, 1 = in progress, 2 = done
        let mut state = vec![0u8; n];
        let mut order = Vec::new();
        for start in 0..n {
            if state[start] != 0 || !self.has_init[start] {
                continue;
            }
            // Iterative DFS: (node, next dependency index).
            let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
            state[start] = 1;
            while let Some(&mut (node, ref mut next)) = stack.last_mut() {
                let deps = self
                    .init_deps
                    .get(node)
                    .map(|d| d.as_slice())
                    .unwrap_or(&[]);
                if let Some(&dep) = deps.get(*next) {
                    *next += 1;
                    let d = dep.0 as usize;
                    match state[d] {
                        0 if self.has_init[d] => {
                            state[d] = 1;
                            stack.push((d, 0));
                        }
                        1 => {
                            let g = &self.globals[d];
                            let (name, span) = (g.name.clone(), g.span);
                            self.err(K::InitCycle { name }, span);
                            state[d] = 2;
                        }
                        _ => {}
                    }
                } else {
                    state[node] = 2;
                    order.push(GlobalId(node as u32));
                    stack.pop();
                }
            }
        }
        order
    }
}
