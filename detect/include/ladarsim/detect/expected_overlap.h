#pragma once
// Expected average overlap (EAO), as the VOT challenge defines it (Kristan et al. 2015, 2016;
// the legacy toolkit's estimate_expected_overlap). docs/detection.md walks through an example.
#include <utility>
#include <vector>

namespace ladarsim::detect {

/// A run of frames from a (re-)initialisation to a failure or the end of the sequence.
struct Fragment {
    std::vector<double> overlaps;  ///< per frame, the initialisation frame first
    bool ends_in_failure = false;
};

/// Cuts a supervised run into fragments. `overlap[i]` is frame i's IoU, `initialised[i]` marks
/// the frames where the tracker was (re-)initialised; frames between a failure (overlap 0) and
/// the next initialisation are skipped.
std::vector<Fragment> fragments_of(const std::vector<double>& overlap, const std::vector<bool>& initialised);

/// Phi(N) = the average over usable fragments of (1 / (N - 1)) sum_{i=2..N} overlap_i: a fragment
/// that ends in a failure is padded with zeros to N, one that does not is usable only when it
/// covers N frames. NaN when no fragment is usable.
double expected_overlap(const std::vector<Fragment>& fragments, int n);

/// EAO: the mean of Phi(N) over N in [lo, hi] (the N with no usable fragment are skipped).
double expected_average_overlap(const std::vector<Fragment>& fragments, int lo, int hi);

/// VOT's rule for [lo, hi]: the interval about the peak of the sequence-length distribution (a
/// Gaussian kernel density, Silverman's bandwidth) holding half its mass; [L, L] for one length.
std::pair<int, int> vot_length_interval(const std::vector<int>& sequence_lengths);

}  // namespace ladarsim::detect
