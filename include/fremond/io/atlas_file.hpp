#pragma once
/// @file An atlas (atlas/atlas.hpp) as files: NumPy arrays (an .npz) and CSV, their names and
/// columns those of docs/atlas.md.
#include <string>
#include <vector>

#include "fremond/atlas/atlas.hpp"
#include "fremond/io/npz.hpp"

namespace fremond::io {

/// The atlas as named arrays: its axes and fixed values (`laws`, `values`, `spins`, `theta`,
/// `psi`, `parameter`, `reference`, `e`, `mu`, `speed`, `contact`, `fremond_k_N`, ...), the
/// configurations' arrays of shape (spins, θ, ψ) and the points' of shape (laws, values, spins,
/// θ, ψ), a trailing 3 for velocities; the codes' names as `failed_names`, `status_names`,
/// `mode_names` (code i is name i).
std::vector<NpyArray> atlas_arrays(const AtlasResult& atlas);

/// npz_archive(atlas_arrays(atlas)).
std::string atlas_npz(const AtlasResult& atlas);

/// The CSV's header row, without its newline.
extern const char* const kAtlasCsvHeader;

/// One header row, then one row per point in index order (ψ fastest), each number in the shortest
/// text that reads back to the same double (`nan` where a solve did not converge), the codes by
/// their names.
std::string atlas_csv(const AtlasResult& atlas);

}  // namespace fremond::io
