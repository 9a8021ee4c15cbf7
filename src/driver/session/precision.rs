//! `:precision [N|off]`: how the session prints parameters, as `lsys
//! derive` does (the shortest form that reads back, or `--precision N`
//! decimal places). Input: the argument; output: the style every view of
//! the string then uses.

use super::{Out, Session};
use crate::derive::{NumberFormat, NumberStyle};
use crate::resolve::ir::Program;

impl Session {
    /// How `program`'s parameters print in this session.
    pub(super) fn numbers(&self, program: &Program) -> NumberFormat {
        NumberFormat::for_program(program).with_style(self.number_style)
    }

    /// `:precision [N|off]`: shows or sets the style, then the string.
    pub fn precision(&mut self, arg: &str) -> Out {
        match arg.trim() {
            "" => {}
            "off" | "shortest" => self.number_style = NumberStyle::Shortest,
            n => {
                let places: u8 = n.parse().map_err(|_| {
                    format!("`:precision` takes a number of decimal places (0 to 255) or `off`, not `{n}`")
                })?;
                self.number_style = NumberStyle::Decimals(places);
            }
        }
        let what = match self.number_style {
            NumberStyle::Decimals(n) => format!(
                "parameters print rounded to {n} decimal places, as `lsys derive --precision {n}` (`:precision off` for the shortest form)"
            ),
            _ => "parameters print in the shortest form that reads back, as `lsys derive` (`:precision N` rounds them)".to_string(),
        };
        Ok(match self.grammar {
            Some(_) => format!("{what}\n{}", self.status()),
            None => what,
        })
    }
}
