//! Contactor nodes that a support holds along their contact normal (`[[contact]]
//! supported_contactors`, 2D and 3D): such a node cannot take part in contact (its relative
//! normal displacement is prescribed). `refuse` (the default) stops with the list of them and
//! the key that leaves them out; `leave_out` drops them from their zone with a warning naming
//! them (printed by `bipo check` and `bipo run`, and in `summary.json`'s `warnings`).

use crate::error::{CliResult, KeyPath, bail};
use crate::scene::SupportedContactors;

/// Nodes named in full in a message; the rest are counted.
const LISTED: usize = 10;

/// One zone's policy: its key path (`contact[i]`), name, contactor set and choice.
pub(super) struct Policy<'a> {
    pub(super) path: KeyPath,
    pub(super) name: &'a str,
    pub(super) contactor: &'a str,
    pub(super) choice: SupportedContactors,
}

/// The nodes `held` (`(zone, node)`, as the library finds them) under each zone's policy: per
/// zone the nodes to leave out, and the warnings; an error at the first zone that refuses
/// them. `position` writes a node's reference position.
pub(super) fn resolve(
    held: &[(usize, usize)],
    policies: &[Policy<'_>],
    position: &dyn Fn(usize) -> String,
) -> CliResult<(Vec<Vec<usize>>, Vec<String>)> {
    let mut leave_out = vec![Vec::new(); policies.len()];
    let mut warnings = Vec::new();
    for (z, policy) in policies.iter().enumerate() {
        let nodes: Vec<usize> = held
            .iter()
            .filter(|(zone, _)| *zone == z)
            .map(|&(_, n)| n)
            .collect();
        if nodes.is_empty() {
            continue;
        }
        let list = listing(&nodes, position);
        let key = policy.path.key("supported_contactors");
        match policy.choice {
            SupportedContactors::Refuse => {
                let cp = policy.path.key("contactor");
                bail!(
                    cp,
                    "`{cp}` = \"{}\": {} of its nodes carry a support that holds them along \
                         the contact normal, so they cannot take part in contact: {list}; set \
                         `{key} = \"leave_out\"` to leave them out of zone `{}` (or remove \
                         those supports)",
                    policy.contactor,
                    nodes.len(),
                    policy.name
                );
            }
            SupportedContactors::LeaveOut => {
                warnings.push(format!(
                    "zone `{}`: {} contactor node(s) held along the contact normal by a \
                     support are left out ({key} = \"leave_out\"): {list}",
                    policy.name,
                    nodes.len()
                ));
                leave_out[z] = nodes;
            }
        }
    }
    Ok((leave_out, warnings))
}

/// "node 3 at (0, 1), node 7 at (1, 1)", at most [`LISTED`] then "and N more".
fn listing(nodes: &[usize], position: &dyn Fn(usize) -> String) -> String {
    let mut parts: Vec<String> = nodes
        .iter()
        .take(LISTED)
        .map(|&n| format!("node {n} at {}", position(n)))
        .collect();
    if nodes.len() > LISTED {
        parts.push(format!("and {} more", nodes.len() - LISTED));
    }
    parts.join(", ")
}

/// `(x, y)` or `(x, y, z)`.
pub(super) fn point(x: &[f64]) -> String {
    let each: Vec<String> = x.iter().map(|v| format!("{v}")).collect();
    format!("({})", each.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolve_lists_ten_then_counts_works() {
        let held: Vec<(usize, usize)> = (0..12).map(|n| (0, n)).collect();
        let refuse = [Policy {
            path: KeyPath::root().key("contact").index(0),
            name: "base",
            contactor: "bottom",
            choice: SupportedContactors::Refuse,
        }];
        let e = resolve(&held, &refuse, &|n| point(&[n as f64, 0.0])).unwrap_err();
        assert_eq!(e.path.unwrap().to_string(), "contact[0].contactor");
        assert!(
            e.message.contains("node 9 at (9, 0), and 2 more"),
            "{}",
            e.message
        );
        assert!(
            e.message
                .contains("contact[0].supported_contactors = \"leave_out\"")
        );
        let leave = [Policy {
            choice: SupportedContactors::LeaveOut,
            ..refuse.into_iter().next().unwrap()
        }];
        let (out, warnings) = resolve(&held[..2], &leave, &|n| point(&[n as f64])).unwrap();
        assert_eq!(out, [vec![0, 1]]);
        assert_eq!(warnings.len(), 1);
        assert!(
            warnings[0].contains("node 0 at (0), node 1 at (1)"),
            "{}",
            warnings[0]
        );
    }
}
