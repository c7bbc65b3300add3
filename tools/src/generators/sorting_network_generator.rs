//! Generator of `src/polygon/sorting_networks_generated.rs`: optimal sorting networks for
//! bitonic sequences of up to 8 elements (Peters 2021, supplemental document, section A.6,
//! Table A.1), found by an exhaustive search that proves its own optimality.
//!
//! # What is searched
//!
//! A network is a sequence of comparators `(i, j)`, `i < j`: entries `i` and `j` are
//! swapped if entry `j` is less than entry `i`. It must sort (ascending) every *bitonic*
//! sequence of `n` entries: every cyclic rotation of a sequence that first does not
//! decrease and then does not increase, ties allowed.
//!
//! # The 0-1 principle: ties change nothing
//!
//! A comparator network commutes with every monotone map `f` applied entrywise. If a
//! network left a bitonic input `x` unsorted, with output entries `y_p > y_{p+1}`, the
//! threshold `f(v) = [v >= y_p]` would turn `x` into a 0-1 sequence that the network
//! leaves unsorted too. A threshold of a bitonic sequence is a 0-1 sequence whose ones
//! form one cyclic run (the upper level sets of a unimodal sequence are intervals), and
//! each such sequence is itself bitonic and the threshold of a bitonic permutation of
//! `0..n`. Hence, for every network, these are equivalent:
//!
//! - it sorts every bitonic sequence with ties,
//! - it sorts every bitonic permutation of distinct values,
//! - it sorts the `n (n - 1) + 2` 0-1 sequences whose ones form one cyclic run.
//!
//! So the comparison counts of Table A.1 hold with ties, and the search only tracks the
//! 0-1 sequences. (The core's tests still check every bitonic sequence with and without
//! ties directly.)
//!
//! # The search
//!
//! A state is the *set* of distinct 0-1 sequences that the comparators so far turn the
//! test sequences into, stored as a 256-bit set indexed by the sequence read as a binary
//! number (bit `p` = entry `p`); a comparator acts on the whole set with a few shifts and
//! masks. The goal state holds only sorted sequences (one per number of ones). A
//! depth-first search with a budget `r` of comparators tries every comparator on each
//! state, skipping those that change no sequence of the state (removing such a
//! comparator from a network changes no output and adds no layer), and prunes:
//!
//! - states already known to fail with at least the same budget (memoised);
//! - with a cheap lower bound: every channel whose entry differs from its sorted value
//!   in some sequence must be touched (`ceil(wrong channels / 2)` comparators), and a
//!   comparator at most halves the number of distinct sequences with `k` ones, of which
//!   exactly one must remain;
//! - with exact sub-problems: the sequences with `1`, `k` and `n - 1` ones (for each
//!   middle `k`) must be sorted by the same network, so if that subset alone cannot be
//!   sorted within the budget, neither can the state. The subsets are solved by the same
//!   search (memoising the proven lower and upper bounds per subset), pruned in turn by
//!   their subsets with the sequences of one number of ones left out, down to single
//!   numbers of ones. The subsets are far fewer than the states, and this bound is what
//!   makes proving the 8-element case (no network with 11 comparisons) take seconds
//!   instead of hours;
//! - when the depth is limited: the single 0 of the sequences with `n - 1` ones must
//!   reach channel 0 (and the single 1 of those with one 1 channel `n - 1`), and the
//!   channels that can still flow into one channel at most double with every layer back
//!   from the limit (see `Search::too_shallow`).
//!
//! Every pruning rule only discards states that provably cannot reach the goal within
//! the budget, so a failed search with budget `r` proves that no network with at most
//! `r` comparators exists. The generator increases the budget from 0 until a network is
//! found: the first budget that succeeds is the minimal comparison count (proven, for
//! every `n` including 7 and 8; the paper reports the 7-element proof took 5.5 GPU
//! hours of brute force). Then, with that count fixed, it adds a limit on the depth
//! (each comparator placed in the layer after the last layer of its two channels) and
//! raises that limit from 1 until a network is found: the result has the minimal depth
//! among networks with the minimal count (also proven; the memo key then includes the
//! channels' layers). The search order is deterministic (the children of a state with
//! the fewest distinct sequences first, then in lexicographic comparator order, which
//! only speeds up finding), so regeneration reproduces the file exactly. The networks
//! are written sorted by layer, then by channel.
//!
//! All of this, for every size, takes about 15 s at opt-level 3 (almost all of it for 8
//! elements: about 8 s to prove 11 comparisons impossible, 5 s to find 12).
//!
//! The paper also made the networks of different sizes share their last comparisons to
//! save conditional code on a GPU; that is not done here (the generated function jumps
//! to one straight-line block per size).
use std::collections::HashMap;
use std::fmt::Write as _;

/// The most elements a network sorts (the capacity of the polygon vertex array).
pub const MAX_ELEMENTS: usize = 8;

/// Table A.1 of the supplement (comparisons of the bitonic networks), indexed by the
/// element count; counts 0 to 2 (none, none, one comparison) complete it.
pub const TABLE_A1: [usize; MAX_ELEMENTS + 1] = [0, 0, 1, 3, 4, 8, 9, 12, 12];

/// A comparator `(i, j)` with `i < j`.
pub type Comparator = (usize, usize);

/// A set of 0-1 sequences of up to 8 entries: bit `m` is set iff sequence `m` (entry `p`
/// is bit `p` of `m`) is present.
type Set = [u64; 4];

const EMPTY: Set = [0; 4];

fn insert(set: &mut Set, sequence: usize) {
    set[sequence >> 6] |= 1 << (sequence & 63);
}

fn and(a: &Set, b: &Set) -> Set {
    std::array::from_fn(|w| a[w] & b[w])
}

fn is_empty(set: &Set) -> bool {
    set.iter().all(|&w| w == 0)
}

fn len(set: &Set) -> u32 {
    set.iter().map(|w| w.count_ones()).sum()
}

/// `set` shifted towards higher sequences by `by` (the sequences move from `m` to
/// `m + by`; nothing may move past 255).
fn shift_up(set: &Set, by: usize) -> Set {
    let (words, bits) = (by / 64, by % 64);
    let mut out = EMPTY;
    for w in words..4 {
        out[w] = set[w - words] << bits;
        if bits > 0 && w > words {
            out[w] |= set[w - words - 1] >> (64 - bits);
        }
    }
    out
}

/// The sorted sequence of `n` entries with `ones` ones (ones in the top entries).
fn sorted_sequence(n: usize, ones: usize) -> usize {
    ((1 << ones) - 1) << (n - ones)
}

/// The 0-1 sequences of `n` entries whose ones form one cyclic run (including none and
/// all): the thresholds of the bitonic sequences.
fn bitonic_zero_one_sequences(n: usize) -> Set {
    let mut set = EMPTY;
    for start in 0..n {
        for ones in 0..=n {
            let sequence = (0..ones).fold(0, |m, k| m | 1 << ((start + k) % n));
            insert(&mut set, sequence);
        }
    }
    set
}

/// Applies comparator `(i, j)` to one 0-1 sequence.
fn compare_exchange_bits(sequence: usize, (i, j): Comparator) -> usize {
    if sequence >> i & 1 == 1 && sequence >> j & 1 == 0 {
        sequence ^ (1 << i | 1 << j)
    } else {
        sequence
    }
}

/// Whether `network` sorts every 0-1 sequence whose ones form one cyclic run, i.e. (by
/// the 0-1 principle) every bitonic sequence of `n` entries.
pub fn sorts_every_bitonic_sequence(n: usize, network: &[Comparator]) -> bool {
    let inputs = bitonic_zero_one_sequences(n);
    (0..1usize << n)
        .filter(|&m| inputs[m >> 6] >> (m & 63) & 1 == 1)
        .all(|m| {
            let out = network.iter().fold(m, |m, &c| compare_exchange_bits(m, c));
            out == sorted_sequence(n, m.count_ones() as usize)
        })
}

/// The number of layers when every comparator goes into the layer after the last layer
/// that uses one of its channels.
pub fn depth(network: &[Comparator]) -> usize {
    layers(network).into_iter().max().unwrap_or(0)
}

/// The layer (1-based) of each comparator of `network`.
fn layers(network: &[Comparator]) -> Vec<usize> {
    let mut channel = [0; MAX_ELEMENTS];
    network
        .iter()
        .map(|&(i, j)| {
            let layer = channel[i].max(channel[j]) + 1;
            channel[i] = layer;
            channel[j] = layer;
            layer
        })
        .collect()
}

/// The same network with its comparators ordered by layer, then by channel (comparators
/// of one layer touch distinct channels, so this changes no result).
fn by_layers(network: &[Comparator]) -> Vec<Comparator> {
    let mut ordered: Vec<(usize, Comparator)> = layers(network)
        .into_iter()
        .zip(network.iter().copied())
        .collect();
    ordered.sort();
    ordered.into_iter().map(|(_, c)| c).collect()
}

/// The exhaustive search for one element count (see the module documentation).
struct Search {
    n: usize,
    goal: Set,
    /// Per comparator `i * 8 + j`: the sequences it changes and how far they move.
    comparators: Vec<(Comparator, Set, usize)>,
    /// Per channel: the sequences whose entry there differs from the sorted one.
    wrong_at: Vec<Set>,
    /// Per number of ones `k` in `0..=n`: all sequences with `k` ones.
    classes: Vec<Set>,
    /// The sub-problems: unions of classes (as bit masks over `k`).
    groups: Vec<u32>,
    /// The depth limit (`usize::MAX`: none).
    max_depth: usize,
    /// Full states (and channel layers if depth-limited) known to fail with this budget.
    failed: HashMap<(Set, [u8; MAX_ELEMENTS]), u8>,
    /// Sub-problems: (budget proven insufficient + 1, budget proven sufficient).
    bounds: HashMap<Set, (u8, u8)>,
    /// Visited full states (statistics).
    nodes: u64,
}

impl Search {
    fn new(n: usize) -> Self {
        assert!((1..=MAX_ELEMENTS).contains(&n));
        let all = 0..1usize << n;
        let set_of = |keep: &dyn Fn(usize) -> bool| {
            let mut set = EMPTY;
            all.clone()
                .filter(|&m| keep(m))
                .for_each(|m| insert(&mut set, m));
            set
        };
        let wrong = |m: usize| m ^ sorted_sequence(n, m.count_ones() as usize);
        let bit = |k: usize| 1u32 << k;
        let groups = if n >= 4 {
            (2..n - 1).map(|k| bit(1) | bit(k) | bit(n - 1)).collect()
        } else if n == 3 {
            vec![bit(1) | bit(2)]
        } else {
            Vec::new()
        };
        Search {
            n,
            goal: set_of(&|m| wrong(m) == 0),
            comparators: (0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .map(|c| {
                    let moved = set_of(&|m| compare_exchange_bits(m, c) != m);
                    (c, moved, (1 << c.1) - (1 << c.0))
                })
                .collect(),
            wrong_at: (0..n)
                .map(|p| set_of(&|m| wrong(m) >> p & 1 == 1))
                .collect(),
            classes: (0..=n)
                .map(|k| set_of(&|m| m.count_ones() as usize == k))
                .collect(),
            groups,
            max_depth: usize::MAX,
            failed: HashMap::new(),
            bounds: HashMap::new(),
            nodes: 0,
        }
    }

    /// Applies comparator number `c` to every sequence of `set`.
    fn apply(&self, set: &Set, c: usize) -> Set {
        let (_, moved, by) = &self.comparators[c];
        let shifted = shift_up(&and(set, moved), *by);
        std::array::from_fn(|w| set[w] & !moved[w] | shifted[w])
    }

    /// Cheap lower bound on the comparators that sort `set` (any subset of sequences).
    fn quick_bound(&self, set: &Set) -> usize {
        let wrong = self
            .wrong_at
            .iter()
            .filter(|bad| !is_empty(&and(set, bad)))
            .count();
        let largest_class = self
            .classes
            .iter()
            .map(|class| len(&and(set, class)))
            .max()
            .unwrap_or(0);
        wrong
            .div_ceil(2)
            .max(largest_class.next_power_of_two().trailing_zeros() as usize)
    }

    /// Whether the depth limit is provably too small for `set`: the single 0 of the
    /// sequences with `n - 1` ones must reach channel 0, and the single 1 of those with
    /// one 1 must reach channel `n - 1`. The channels whose value, as of layer `t`, can
    /// still flow into one channel by layer `D` (the depth limit) at most double with
    /// every layer back from `D`, so at most `2^(D - t)` of the channels where the 0 (or
    /// the 1) may be, with their last comparator in layer `t` or later, are allowed.
    fn too_shallow(&self, set: &Set, channel_layers: &[u8; MAX_ELEMENTS]) -> bool {
        let n = self.n;
        let contains = |m: usize| set[m >> 6] >> (m & 63) & 1 == 1;
        let all = (1usize << n) - 1;
        [
            (0..n)
                .filter(|&p| contains(all ^ 1 << p))
                .collect::<Vec<_>>(),
            (0..n).filter(|&p| contains(1 << p)).collect(),
        ]
        .iter()
        .any(|channels| {
            channels.iter().any(|&p| {
                let t = channel_layers[p] as usize;
                let later = channels
                    .iter()
                    .filter(|&&q| channel_layers[q] as usize >= t)
                    .count();
                self.max_depth - t < MAX_ELEMENTS && later > 1 << (self.max_depth - t)
            })
        })
    }

    /// Whether the sub-problem `set` (any subset of sequences) can be sorted with at most
    /// `budget` comparators. Memoised; pruned by its subsets with one class left out.
    fn subset_sortable(&mut self, set: Set, budget: usize) -> bool {
        if is_empty(&std::array::from_fn(|w| set[w] & !self.goal[w])) {
            return true;
        }
        if budget == 0 || self.quick_bound(&set) > budget {
            return false;
        }
        let (insufficient_below, sufficient) =
            self.bounds.get(&set).copied().unwrap_or((0, u8::MAX));
        if budget < insufficient_below as usize {
            return false;
        }
        if budget >= sufficient as usize {
            return true;
        }
        let spanned: Vec<usize> = (0..=self.n)
            .filter(|&k| !is_empty(&and(&set, &self.classes[k])))
            .collect();
        let mut sortable = true;
        if spanned.len() > 1 && budget >= 3 {
            for leave_out in spanned {
                let class = self.classes[leave_out];
                let subset = std::array::from_fn(|w| set[w] & !class[w]);
                if !self.subset_sortable(subset, budget) {
                    sortable = false;
                    break;
                }
            }
        }
        if sortable {
            let mut children: Vec<(u32, usize, Set)> = (0..self.comparators.len())
                .map(|c| {
                    let next = self.apply(&set, c);
                    (len(&next), c, next)
                })
                .filter(|&(_, _, next)| next != set)
                .collect();
            children.sort_by_key(|&(size, c, _)| (size, c));
            sortable = children
                .into_iter()
                .any(|(_, _, next)| self.subset_sortable(next, budget - 1));
        }
        let entry = self.bounds.entry(set).or_insert((0, u8::MAX));
        if sortable {
            entry.1 = entry.1.min(budget as u8);
        } else {
            entry.0 = entry.0.max(budget as u8 + 1);
        }
        sortable
    }

    /// Depth-first search: appends to `network` comparators that sort `set` within
    /// `budget` comparators and the depth limit, or returns false if there are none.
    fn sortable(
        &mut self,
        set: Set,
        channel_layers: [u8; MAX_ELEMENTS],
        budget: usize,
        network: &mut Vec<Comparator>,
    ) -> bool {
        self.nodes += 1;
        if set == self.goal {
            return true;
        }
        if budget == 0 || self.quick_bound(&set) > budget {
            return false;
        }
        if self.max_depth != usize::MAX && self.too_shallow(&set, &channel_layers) {
            return false;
        }
        let key = (set, channel_layers);
        if self.failed.get(&key).is_some_and(|&b| b as usize >= budget) {
            return false;
        }
        let mut pruned = false;
        if budget >= 3 {
            for g in 0..self.groups.len() {
                let group = self.groups[g];
                let mut subset = EMPTY;
                for (k, class) in self.classes.iter().enumerate() {
                    if group >> k & 1 == 1 {
                        (0..4).for_each(|w| subset[w] |= set[w] & class[w]);
                    }
                }
                if !self.subset_sortable(subset, budget) {
                    pruned = true;
                    break;
                }
            }
        }
        if !pruned {
            // Children with fewer distinct sequences first (then in comparator order):
            // this only speeds up finding a network, a failure still tries all.
            let mut children = Vec::new();
            for c in 0..self.comparators.len() {
                let (i, j) = self.comparators[c].0;
                let layer = channel_layers[i].max(channel_layers[j]) + 1;
                if layer as usize > self.max_depth {
                    continue;
                }
                let next = self.apply(&set, c);
                if next != set {
                    children.push((len(&next), c, next, layer));
                }
            }
            children.sort_by_key(|&(size, c, _, _)| (size, c));
            for (_, c, next, layer) in children {
                let (i, j) = self.comparators[c].0;
                let mut next_layers = channel_layers;
                if self.max_depth != usize::MAX {
                    next_layers[i] = layer;
                    next_layers[j] = layer;
                }
                network.push((i, j));
                if self.sortable(next, next_layers, budget - 1, network) {
                    return true;
                }
                network.pop();
            }
        }
        self.failed.insert(key, budget as u8);
        false
    }

    /// A network with at most `comparisons` comparators and at most `max_depth` layers
    /// that sorts every bitonic sequence, if there is one.
    fn find(&mut self, comparisons: usize, max_depth: usize) -> Option<Vec<Comparator>> {
        if max_depth != self.max_depth {
            self.max_depth = max_depth;
            self.failed.clear();
        }
        let mut network = Vec::new();
        let start = bitonic_zero_one_sequences(self.n);
        self.sortable(start, [0; MAX_ELEMENTS], comparisons, &mut network)
            .then_some(network)
    }
}

/// A network with at most `comparisons` comparators (and at most `max_depth` layers)
/// that sorts every bitonic sequence of `n` elements, or `None` if the exhaustive search
/// proves there is none.
pub fn search(n: usize, comparisons: usize, max_depth: Option<usize>) -> Option<Vec<Comparator>> {
    Search::new(n).find(comparisons, max_depth.unwrap_or(usize::MAX))
}

/// An optimal network for bitonic sequences of `n` elements and how it was proven so.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OptimalNetwork {
    /// The element count, 1 to [`MAX_ELEMENTS`].
    pub elements: usize,
    /// The comparators, ordered by layer, then by channel.
    pub comparators: Vec<Comparator>,
    /// The number of layers.
    pub depth: usize,
    /// Full states the search visited (all budgets and depth limits).
    pub visited_states: u64,
}

/// Finds the network for `n` elements with the fewest comparators and, among those, the
/// smallest depth; both minima are proven by the exhaustive search.
pub fn optimal_network(n: usize) -> OptimalNetwork {
    let mut search = Search::new(n);
    let (comparisons, network) = (0..)
        .find_map(|budget| search.find(budget, usize::MAX).map(|net| (budget, net)))
        .expect("the search terminates: Batcher's networks exist");
    assert_eq!(
        network.len(),
        comparisons,
        "a smaller budget would have succeeded"
    );
    let network = (1..=comparisons.max(1))
        .find_map(|max_depth| search.find(comparisons, max_depth))
        .unwrap_or(network);
    assert_eq!(network.len(), comparisons);
    OptimalNetwork {
        elements: n,
        depth: depth(&network),
        comparators: by_layers(&network),
        visited_states: search.nodes,
    }
}

/// The optimal networks for 1 to [`MAX_ELEMENTS`] elements.
pub fn optimal_networks() -> Vec<OptimalNetwork> {
    (1..=MAX_ELEMENTS).map(optimal_network).collect()
}

fn layer_listing(network: &[Comparator]) -> String {
    let layer_of = layers(network);
    let mut parts = Vec::new();
    for layer in 1..=depth(network) {
        let pairs: Vec<String> = network
            .iter()
            .zip(&layer_of)
            .filter(|&(_, &l)| l == layer)
            .map(|(&(i, j), _)| format!("({i}, {j})"))
            .collect();
        parts.push(pairs.join(" "));
    }
    parts.join("; ")
}

/// The complete text of `src/polygon/sorting_networks_generated.rs` (deterministic).
pub fn generate() -> String {
    render(&optimal_networks())
}

/// Renders the generated file for `networks` (1 to [`MAX_ELEMENTS`] elements, in order).
pub fn render(networks: &[OptimalNetwork]) -> String {
    assert_eq!(networks.len(), MAX_ELEMENTS);
    let mut out = String::new();
    out.push_str(
        "// Generated by `cargo run --release -p sphera-tools --bin generate_sorting_networks`\n\
         // from tools/src/generators/sorting_network_generator.rs. Do not edit: edit the generator and\n\
         // rerun it.\n\
         //! Optimal sorting networks for bitonic sequences of up to 8 elements (Peters 2021,\n\
         //! supplemental document, section A.6). See [`super::sorting_networks`].\n\
         //!\n\
         //! Found by an exhaustive search that proves, for every element count, that no\n\
         //! network with fewer comparators exists and that no network with as many\n\
         //! comparators has fewer layers (see the generator's documentation).\n\
         //!\n\
         //! | elements | comparisons | depth | layers (`;` between layers) |\n\
         //! |---|---|---|---|\n",
    );
    for net in networks {
        writeln!(
            out,
            "//! | {} | {} | {} | {} |",
            net.elements,
            net.comparators.len(),
            net.depth,
            if net.comparators.is_empty() {
                "-".to_string()
            } else {
                layer_listing(&net.comparators)
            }
        )
        .unwrap();
    }
    out.push('\n');
    for net in networks.iter().filter(|net| net.elements >= 2) {
        let pairs: Vec<String> = net
            .comparators
            .iter()
            .map(|&(i, j)| format!("({i}, {j})"))
            .collect();
        writeln!(
            out,
            "/// The comparators `(i, j)` of the network for bitonic sequences of {} elements\n\
             /// ({} comparison{}, depth {}): swap entries `i < j` if entry `j` is less.\n\
             #[allow(dead_code)] // The tables are read by the tests; the sampler runs sort_bitonic.\n\
             pub(crate) const BITONIC_NETWORK_{}: [(u8, u8); {}] = [{}];\n",
            net.elements,
            net.comparators.len(),
            if net.comparators.len() == 1 { "" } else { "s" },
            net.depth,
            net.elements,
            net.comparators.len(),
            pairs.join(", ")
        )
        .unwrap();
    }
    out.push_str(
        "/// The networks indexed by element count (none for 0 and 1 elements).\n\
         #[allow(dead_code)] // The tables are read by the tests; the sampler runs sort_bitonic.\n\
         pub(crate) const BITONIC_NETWORKS: [&[(u8, u8)]; 9] = [\n\
         \x20   &[],\n\
         \x20   &[],\n",
    );
    for n in 2..=MAX_ELEMENTS {
        writeln!(out, "    &BITONIC_NETWORK_{n},").unwrap();
    }
    out.push_str(
        "];\n\
         \n\
         /// Sorts the bitonic sequence `items[..count]` ascending with respect to `less` (a\n\
         /// strict order) in place: the network for `count` as straight-line\n\
         /// compare-exchanges, which swap two entries only if the later one is less. A\n\
         /// `count` of 0, 1 or more than 8 does nothing. Entries past `count` are untouched.\n\
         #[inline]\n\
         pub(crate) fn sort_bitonic<T: Copy>(items: &mut [T; 8], count: usize, less: impl Fn(&T, &T) -> bool) {\n\
         \x20   match count {\n",
    );
    for net in networks.iter().filter(|net| net.elements >= 2) {
        writeln!(out, "        {} => {{", net.elements).unwrap();
        for &(i, j) in &net.comparators {
            writeln!(
                out,
                "            let (a, b) = (items[{i}], items[{j}]);\n\
                 \x20           let swap = less(&b, &a);\n\
                 \x20           items[{i}] = if swap {{ b }} else {{ a }};\n\
                 \x20           items[{j}] = if swap {{ a }} else {{ b }};"
            )
            .unwrap();
        }
        out.push_str("        }\n");
    }
    out.push_str(
        "        _ => {}\n\
         \x20   }\n\
         }\n",
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every cyclic rotation of every non-decreasing-then-non-increasing sequence over
    /// `0..n`, checked independently of the 0-1 reasoning.
    fn is_bitonic(x: &[usize]) -> bool {
        let n = x.len();
        let signs: Vec<bool> = (0..n)
            .filter(|&i| x[(i + 1) % n] != x[i])
            .map(|i| x[(i + 1) % n] > x[i])
            .collect();
        let changes = (0..signs.len())
            .filter(|&i| signs[i] != signs[(i + 1) % signs.len()])
            .count();
        changes <= 2
    }

    fn sorts_all_bitonic_sequences_with_ties(n: usize, network: &[Comparator]) -> bool {
        (0..n.pow(n as u32)).all(|code| {
            let mut x: Vec<usize> = (0..n).map(|p| code / n.pow(p as u32) % n).collect();
            if !is_bitonic(&x) {
                return true;
            }
            for &(i, j) in network {
                if x[j] < x[i] {
                    x.swap(i, j);
                }
            }
            x.windows(2).all(|w| w[0] <= w[1])
        })
    }

    #[test]
    fn minimal_comparison_counts_are_those_of_table_a1() {
        for (n, &count) in TABLE_A1.iter().enumerate().take(7).skip(1) {
            assert_eq!(optimal_network(n).comparators.len(), count, "{n} elements");
        }
    }

    /// The search proves Table A.1 optimal: with one comparator fewer it finds nothing,
    /// for every size, 7 and 8 included (the paper's 7-element proof took 5.5 GPU hours).
    #[test]
    fn no_network_with_one_comparison_fewer_exists() {
        for (n, &count) in TABLE_A1.iter().enumerate().skip(3) {
            assert_eq!(search(n, count - 1, None), None, "{n} elements");
            assert!(search(n, count, None).is_some(), "{n} elements");
        }
    }

    /// With the Table A.1 count, one layer fewer than the generated depth is impossible.
    #[test]
    fn no_network_with_as_many_comparisons_has_fewer_layers() {
        let depths = [0, 0, 1, 3, 2, 4, 4, 4, 3];
        for (n, (&count, &layers)) in TABLE_A1.iter().zip(&depths).enumerate().skip(3) {
            assert_eq!(search(n, count, Some(layers - 1)), None, "{n} elements");
            let network = search(n, count, Some(layers)).expect("exists");
            assert_eq!(depth(&network), layers, "{n} elements");
        }
    }

    #[test]
    fn found_networks_sort_every_bitonic_sequence_including_ties() {
        for n in 2..=6 {
            let net = optimal_network(n);
            assert!(sorts_every_bitonic_sequence(n, &net.comparators));
            assert!(sorts_all_bitonic_sequences_with_ties(n, &net.comparators));
        }
    }

    /// The 0-1 check agrees with the direct check on random networks (both directions).
    #[test]
    fn zero_one_check_agrees_with_checking_all_sequences_with_ties() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut agreed_sorting = 0;
        for _ in 0..3000 {
            let n = 3 + (next() % 3) as usize;
            let len = (next() % 10) as usize;
            let network: Vec<Comparator> = (0..len)
                .map(|_| {
                    let i = (next() % (n as u64 - 1)) as usize;
                    let j = i + 1 + (next() % (n - 1 - i) as u64) as usize;
                    (i, j)
                })
                .collect();
            let zero_one = sorts_every_bitonic_sequence(n, &network);
            assert_eq!(
                zero_one,
                sorts_all_bitonic_sequences_with_ties(n, &network),
                "{network:?}"
            );
            agreed_sorting += usize::from(zero_one);
        }
        assert!(
            agreed_sorting > 0,
            "no random network sorted: the test proves nothing"
        );
    }

    #[test]
    fn a_network_with_a_missing_comparator_is_rejected() {
        for n in 3..=6 {
            let net = optimal_network(n);
            for skip in 0..net.comparators.len() {
                let mut fewer = net.comparators.clone();
                fewer.remove(skip);
                assert!(!sorts_every_bitonic_sequence(n, &fewer));
            }
        }
    }

    #[test]
    fn depth_of_batchers_merger_for_8_elements_is_3() {
        let batcher = [
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
            (0, 2),
            (1, 3),
            (4, 6),
            (5, 7),
            (0, 1),
            (2, 3),
            (4, 5),
            (6, 7),
        ];
        assert_eq!(depth(&batcher), 3);
        assert!(sorts_every_bitonic_sequence(8, &batcher));
    }
}
