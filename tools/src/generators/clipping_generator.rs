//! Generator of `src/polygon/clip_generated.rs`: straight-line, in-situ code that clips a
//! convex polygon with 3 to 7 vertices to the upper hemisphere `z >= 0`, one match arm
//! per configuration (Peters 2021, supplemental document, section A.1).
//!
//! A configuration is one integer: bits 0..=2 hold the input vertex count `n`, bit `3 + i`
//! is set iff vertex `i` is above the horizon (`z > 0`). For every configuration the
//! generator
//!
//! 1. lists the output of Sutherland–Hodgman clipping in the input's cyclic order: an
//!    above vertex is kept, an edge from an above to a non-above vertex (or back) yields
//!    the point where it meets the horizon;
//! 2. tries every cyclic shift of that output. Output slot `j` either already holds what it
//!    needs (the kept input vertex `j`), or needs a write, which reads one input vertex
//!    (a copy) or two (a horizon point);
//! 3. searches for an order of these writes in which no write destroys an input vertex
//!    that a later write still reads. Candidates without such an order are discarded;
//! 4. keeps the candidate with the fewest writes (ties: the smallest shift).
//!
//! The search over orders is a depth-first search that may perform any write whose target
//! slot no pending write still reads. Performing a write only removes constraints, so
//! this search finds an order whenever any order exists; it is as conclusive as
//! enumerating all permutations, and deterministic (it prefers the lowest slot). Should no
//! shift admit an in-place order, the generator saves the blocking input vertices in local
//! temporaries; [`statistics`] reports whether that ever happens.
//!
//! Configurations whose output would exceed 8 vertices (possible only for non-planar or
//! non-convex input, e.g. every other vertex of a hexagon above) return 0, as do the
//! configurations without any vertex above.
use std::fmt::Write as _;

/// The largest input vertex count handled by the generated code (3 bits of the
/// configuration).
pub const MAX_INPUT: usize = 7;
/// The capacity of the vertex array.
pub const CAPACITY: usize = 8;

/// One vertex of the clipped polygon.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Item {
    /// Input vertex `i`, which is above the horizon.
    Kept(usize),
    /// The horizon point on the edge between the above vertex `above` and the non-above
    /// vertex `below` (adjacent in the input).
    Horizon { above: usize, below: usize },
}

impl Item {
    fn reads(self) -> Vec<usize> {
        match self {
            Item::Kept(i) => vec![i],
            Item::Horizon { above, below } => vec![above, below],
        }
    }
}

/// Sutherland–Hodgman output in the input's cyclic order, starting at vertex 0.
fn clipped_sequence(n: usize, above_mask: u32) -> Vec<Item> {
    let above = |i: usize| above_mask >> i & 1 == 1;
    let mut out = Vec::new();
    for i in 0..n {
        let next = (i + 1) % n;
        if above(i) {
            out.push(Item::Kept(i));
        }
        match (above(i), above(next)) {
            (true, false) => out.push(Item::Horizon {
                above: i,
                below: next,
            }),
            (false, true) => out.push(Item::Horizon {
                above: next,
                below: i,
            }),
            _ => {}
        }
    }
    out
}

/// One statement of generated code.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Step {
    /// Save input vertex `i` in a local temporary before its slot is overwritten.
    Save(usize),
    /// Write `item` to slot `slot`.
    Write { slot: usize, item: Item },
}

/// The code chosen for one configuration.
#[derive(Clone, Debug)]
struct Plan {
    n: usize,
    above_mask: u32,
    /// The number of output vertices (0 if none is above or there would be too many).
    output_count: usize,
    shift: usize,
    steps: Vec<Step>,
    writes: usize,
    temporaries: usize,
}

/// Orders the writes `pending` (slot, item) so that no write destroys an input vertex that
/// a later write still reads. Returns `None` if that is impossible without temporaries,
/// unless `allow_temporaries`, in which case the blocking inputs are saved.
fn order_writes(n: usize, pending: &[(usize, Item)], allow_temporaries: bool) -> Option<Vec<Step>> {
    let mut pending: Vec<(usize, Item)> = pending.to_vec();
    let mut saved = vec![false; n];
    let mut steps = Vec::new();
    // `slot` still holds input vertex `slot` that a pending write other than the one to
    // `slot` itself reads from the array (a write may read its own target: the right-hand
    // side is evaluated first).
    let still_needed = |pending: &[(usize, Item)], saved: &[bool], slot: usize| {
        slot < n
            && !saved[slot]
            && pending
                .iter()
                .any(|&(target, item)| target != slot && item.reads().contains(&slot))
    };
    while !pending.is_empty() {
        // Depth-first search over the orders: any ready write may go first, because a
        // write only removes constraints; taking the lowest ready slot is deterministic.
        if let Some(position) = pending
            .iter()
            .position(|&(slot, _)| !still_needed(&pending, &saved, slot))
        {
            let (slot, item) = pending.remove(position);
            steps.push(Step::Write { slot, item });
            continue;
        }
        if !allow_temporaries {
            return None;
        }
        // Every pending target is still needed: save the lowest one's input vertex.
        let slot = pending
            .iter()
            .map(|&(slot, _)| slot)
            .min()
            .expect("non-empty");
        saved[slot] = true;
        steps.push(Step::Save(slot));
    }
    Some(steps)
}

fn plan(n: usize, above_mask: u32) -> Plan {
    let full = (1u32 << n) - 1;
    let trivial = |output_count| Plan {
        n,
        above_mask,
        output_count,
        shift: 0,
        steps: Vec::new(),
        writes: 0,
        temporaries: 0,
    };
    if above_mask == 0 {
        return trivial(0);
    }
    if above_mask == full {
        return trivial(n);
    }
    let sequence = clipped_sequence(n, above_mask);
    let m = sequence.len();
    if m > CAPACITY {
        return trivial(0);
    }
    let writes_for_shift = |shift: usize| -> Vec<(usize, Item)> {
        (0..m)
            .map(|slot| (slot, sequence[(slot + shift) % m]))
            .filter(|&(slot, item)| item != Item::Kept(slot))
            .collect()
    };
    let mut best: Option<Plan> = None;
    for shift in 0..m {
        let pending = writes_for_shift(shift);
        if best.as_ref().is_some_and(|b| b.writes <= pending.len()) {
            continue;
        }
        if let Some(steps) = order_writes(n, &pending, false) {
            best = Some(Plan {
                n,
                above_mask,
                output_count: m,
                shift,
                steps,
                writes: pending.len(),
                temporaries: 0,
            });
        }
    }
    if let Some(best) = best {
        return best;
    }
    // No in-place order for any shift: fewest writes plus temporaries.
    (0..m)
        .map(|shift| {
            let pending = writes_for_shift(shift);
            let steps = order_writes(n, &pending, true).expect("temporaries always succeed");
            let temporaries = steps.iter().filter(|s| matches!(s, Step::Save(_))).count();
            Plan {
                n,
                above_mask,
                output_count: m,
                shift,
                steps,
                writes: pending.len(),
                temporaries,
            }
        })
        .min_by_key(|p| (p.writes + p.temporaries, p.shift))
        .expect("at least one shift")
}

fn all_plans() -> Vec<Plan> {
    (3..=MAX_INPUT)
        .flat_map(|n| (0..1u32 << n).map(move |mask| plan(n, mask)))
        .collect()
}

/// Summary of the generated code.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Statistics {
    /// Configurations with at least one and not all vertices above whose output fits.
    pub clipping_configurations: usize,
    /// Configurations whose output would exceed [`CAPACITY`] vertices (they return 0).
    pub overflowing_configurations: usize,
    /// The fewest and most writes among the clipping configurations.
    pub min_writes: usize,
    pub max_writes: usize,
    /// How many clipping configurations need `k` writes, indexed by `k`.
    pub writes_histogram: Vec<usize>,
    /// Clipping configurations that needed a temporary.
    pub configurations_with_temporaries: usize,
    /// The same histogram restricted to the configurations that planar convex polygons
    /// can produce (the above vertices form one contiguous run).
    pub contiguous_writes_histogram: Vec<usize>,
}

/// Whether the above vertices form one cyclically contiguous run.
fn is_contiguous(n: usize, above_mask: u32) -> bool {
    let runs = (0..n).filter(|&i| above_mask >> i & 1 == 1 && above_mask >> ((i + 1) % n) & 1 == 0);
    runs.count() == 1
}

/// Statistics of the generated code (for the report and tests).
pub fn statistics() -> Statistics {
    let plans = all_plans();
    let clipping: Vec<&Plan> = plans
        .iter()
        .filter(|p| p.above_mask != 0 && p.above_mask != (1 << p.n) - 1 && p.output_count != 0)
        .collect();
    let overflowing = plans
        .iter()
        .filter(|p| p.above_mask != 0 && p.above_mask != (1 << p.n) - 1 && p.output_count == 0)
        .count();
    let max_writes = clipping.iter().map(|p| p.writes).max().unwrap_or(0);
    let mut writes_histogram = vec![0; max_writes + 1];
    let mut contiguous_writes_histogram = vec![0; max_writes + 1];
    for p in &clipping {
        writes_histogram[p.writes] += 1;
        if is_contiguous(p.n, p.above_mask) {
            contiguous_writes_histogram[p.writes] += 1;
        }
    }
    Statistics {
        clipping_configurations: clipping.len(),
        overflowing_configurations: overflowing,
        min_writes: clipping.iter().map(|p| p.writes).min().unwrap_or(0),
        max_writes,
        writes_histogram,
        configurations_with_temporaries: clipping.iter().filter(|p| p.temporaries > 0).count(),
        contiguous_writes_histogram,
    }
}

fn above_list(n: usize, mask: u32) -> String {
    let list: Vec<String> = (0..n)
        .filter(|&i| mask >> i & 1 == 1)
        .map(|i| i.to_string())
        .collect();
    if list.is_empty() {
        "none".to_string()
    } else {
        list.join(" ")
    }
}

fn emit_plan(out: &mut String, p: &Plan) {
    let configuration = p.n as u32 | p.above_mask << 3;
    let full = (1u32 << p.n) - 1;
    let above = above_list(p.n, p.above_mask);
    let description = if p.above_mask == full {
        "input is the output".to_string()
    } else if p.output_count == 0 {
        format!(
            "{} output vertices do not fit",
            clipped_sequence(p.n, p.above_mask).len()
        )
    } else {
        format!(
            "{} output vertices, shift {}, {} writes{}",
            p.output_count,
            p.shift,
            p.writes,
            if p.temporaries > 0 {
                format!(", {} temporaries", p.temporaries)
            } else {
                String::new()
            }
        )
    };
    writeln!(
        out,
        "        // {} vertices, above: {}; {}",
        p.n, above, description
    )
    .unwrap();
    if p.steps.is_empty() {
        writeln!(out, "        {} => {},", configuration, p.output_count).unwrap();
        return;
    }
    writeln!(out, "        {} => {{", configuration).unwrap();
    let mut saved = vec![false; p.n];
    let read = |i: usize, saved: &[bool]| {
        if saved[i] {
            format!("saved_{i}")
        } else {
            format!("vertices[{i}]")
        }
    };
    for step in &p.steps {
        match *step {
            Step::Save(i) => {
                writeln!(out, "            let saved_{i} = vertices[{i}];").unwrap();
                saved[i] = true;
            }
            Step::Write {
                slot,
                item: Item::Kept(i),
            } => {
                writeln!(out, "            vertices[{slot}] = {};", read(i, &saved)).unwrap();
            }
            Step::Write {
                slot,
                item: Item::Horizon { above, below },
            } => {
                writeln!(
                    out,
                    "            vertices[{slot}] = horizon_point({}, {});",
                    read(above, &saved),
                    read(below, &saved)
                )
                .unwrap();
            }
        }
    }
    writeln!(out, "            {}", p.output_count).unwrap();
    writeln!(out, "        }}").unwrap();
}

/// The complete text of `src/polygon/clip_generated.rs` (deterministic).
pub fn generate() -> String {
    let plans = all_plans();
    let stats = statistics();
    let mut out = String::new();
    out.push_str(
        "// Generated by `cargo run -p sphera-tools --bin generate_clipping` from\n\
         // tools/src/generators/clipping_generator.rs. Do not edit: edit the generator and rerun it.\n",
    );
    out.push_str(
        "//! In-situ clipping of convex polygons with 3 to 7 vertices to the upper hemisphere:\n\
         //! one match arm of straight-line code per configuration (Peters 2021, supplemental\n\
         //! document, section A.1). See [`super::clip::clip_to_upper_hemisphere`].\n\
         //!\n",
    );
    let histogram = |h: &[usize]| {
        let parts: Vec<String> = h
            .iter()
            .enumerate()
            .filter(|&(_, &c)| c > 0)
            .map(|(k, c)| format!("{c} x {k}"))
            .collect();
        parts.join(", ")
    };
    writeln!(
        out,
        "//! {} clipping configurations, {} to {} writes each, {} needing a temporary.\n\
         //! Writes: {}.\n\
         //! Writes of the {} configurations of planar convex polygons: {}.\n\
         //! {} configurations (only non-planar or non-convex input) would exceed {} vertices\n\
         //! and return 0.\n",
        stats.clipping_configurations,
        stats.min_writes,
        stats.max_writes,
        stats.configurations_with_temporaries,
        histogram(&stats.writes_histogram),
        stats.contiguous_writes_histogram.iter().sum::<usize>(),
        histogram(&stats.contiguous_writes_histogram),
        stats.overflowing_configurations,
        CAPACITY,
    )
    .unwrap();
    out.push_str(
        "use glam::Vec3;\n\
         \n\
         use crate::math::difference_of_products;\n\
         \n\
         /// 2^-40: see [`horizon_point`].\n\
         const MIN_DENOMINATOR: f32 = 9.094_947e-13;\n\
         \n\
         /// The point where the edge from `above` (`above.z > 0`) to `below` (`below.z <= 0`)\n\
         /// meets the horizon, anchored at `below`: exactly `below` (with `z = +0.0`) if\n\
         /// `below.z == 0`, else `b + (a - b) b_z / (b_z - a_z)` for `a = above`, `b = below`,\n\
         /// accurate to about an ulp of the larger endpoint. Where the point lies more than 4\n\
         /// times nearer the shading point than that endpoint (an edge passing close to it),\n\
         /// `(a_z b - b_z a) / (a_z - b_z)` per component instead: each numerator a difference\n\
         /// of products (2 ulps, Kahan's algorithm) and the denominator a sum of two\n\
         /// non-negative magnitudes, so every coordinate is accurate to about 3 ulps of\n\
         /// itself (the anchored form was off by up to 4000 ulps of the point for endpoints\n\
         /// 1000 times farther away, and moved a clipped polygon's Φ by 5e-4; issue 16, 3).\n\
         /// That form is not used where the `z`s are both below 2^-40 (products of them may\n\
         /// lose their rounding errors to underflow) or where it overflows. Where a difference\n\
         /// of coordinates near `f32::MAX` overflows, the halved differences and the convex\n\
         /// combination give the finite point (found by fuzzing: an infinite clipped vertex).\n\
         #[inline(always)]\n\
         fn horizon_point(above: Vec3, below: Vec3) -> Vec3 {\n\
         \x20   let mut point = below + (above - below) * (below.z / (below.z - above.z));\n\
         \x20   if !point.is_finite() {\n\
         \x20       let t = below.z / (below.z - above.z);\n\
         \x20       let t = if t.is_finite() {\n\
         \x20           t\n\
         \x20       } else {\n\
         \x20           (0.5 * below.z) / (0.5 * below.z - 0.5 * above.z)\n\
         \x20       };\n\
         \x20       point = below * (1.0 - t) + above * t;\n\
         \x20   }\n\
         \x20   let denominator = above.z - below.z;\n\
         \x20   let far = above.abs().max_element().max(below.abs().max_element());\n\
         \x20   if below.z != 0.0\n\
         \x20       && denominator >= MIN_DENOMINATOR\n\
         \x20       && far > 4.0 * point.abs().max_element()\n\
         \x20   {\n\
         \x20       let accurate = Vec3::new(\n\
         \x20           difference_of_products(above.z, below.x, below.z, above.x) / denominator,\n\
         \x20           difference_of_products(above.z, below.y, below.z, above.y) / denominator,\n\
         \x20           0.0,\n\
         \x20       );\n\
         \x20       if accurate.is_finite() {\n\
         \x20           return accurate;\n\
         \x20       }\n\
         \x20   }\n\
         \x20   point.z = 0.0;\n\
         \x20   point\n\
         }\n\
         \n\
         /// Clips `vertices` in place for `configuration` (bits 0..=2: the input vertex count\n\
         /// 3..=7, bit `3 + i`: vertex `i` has `z > 0`) and returns the output vertex count.\n\
         /// Configurations without a vertex above, with more than 8 output vertices or\n\
         /// with an invalid count return 0.\n\
         pub(crate) fn clip_generated(vertices: &mut [Vec3; 8], configuration: u32) -> usize {\n\
         \x20   match configuration {\n",
    );
    for p in plans.iter().filter(|p| p.output_count != 0) {
        emit_plan(&mut out, p);
    }
    out.push_str(
        "        // No vertex above, more than 8 output vertices, or an invalid count.\n\
         \x20       _ => 0,\n\
         \x20   }\n\
         }\n",
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Executes a plan on symbolic vertices and checks the result is the clipped sequence.
    #[test]
    fn every_plan_produces_the_clipped_sequence_in_place() {
        for p in all_plans() {
            if p.steps.is_empty() {
                continue;
            }
            // Symbolic array: each slot holds an Item (input slots hold Kept(i) initially,
            // even below; slots past n hold garbage).
            let mut slots: Vec<Option<usize>> = (0..CAPACITY)
                .map(|i| if i < p.n { Some(i) } else { None })
                .collect();
            let mut out: Vec<Option<Item>> = vec![None; CAPACITY];
            for (i, o) in out.iter_mut().enumerate().take(p.n) {
                *o = Some(Item::Kept(i));
            }
            let mut temps = vec![None; p.n];
            let fetch = |i: usize, slots: &[Option<usize>], temps: &[Option<usize>]| {
                let v = temps[i].or(slots[i]).expect("slot holds garbage");
                assert_eq!(v, i, "input {i} was overwritten before it was read");
                v
            };
            for step in &p.steps {
                match *step {
                    Step::Save(i) => temps[i] = Some(fetch(i, &slots, &temps)),
                    Step::Write { slot, item } => {
                        for r in item.reads() {
                            fetch(r, &slots, &temps);
                        }
                        slots[slot] = None;
                        out[slot] = Some(item);
                    }
                }
            }
            let sequence = clipped_sequence(p.n, p.above_mask);
            let m = sequence.len();
            for j in 0..m {
                assert_eq!(out[j], Some(sequence[(j + p.shift) % m]));
            }
        }
    }

    #[test]
    fn generation_is_deterministic() {
        assert_eq!(generate(), generate());
    }
}
