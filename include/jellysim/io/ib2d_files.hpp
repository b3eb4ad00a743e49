#pragma once
// IB2d's plain-text structure files (github.com/nickabattista/IB2d) read into and written from an
// elastic::Ib2dStructure. A structure is a stem ("dir/jelly256") and the files STEM.vertex,
// STEM.spring, STEM.d_spring, STEM.beam, STEM.nonInv_beam and STEM.target. Each file is
// whitespace-separated numbers: line 1 holds the row count N, then come N rows:
//   .vertex       x y
//   .spring       master slave k RL [alpha]   (alpha, the degree of nonlinearity, defaults to 1)
//   .d_spring     master slave k RL b         (b: damping coefficient)
//   .beam         left middle right k C
//   .nonInv_beam  left middle right k Cx Cy
//   .target       id k
// Point indices count from 1 in the files and from 0 in the structure.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "jellysim/elastic/ib2d_structure.hpp"

namespace jellysim::io {

/// Largest IB2d structure file read or written.
inline constexpr std::uintmax_t kMaxIb2dFileBytes = std::uintmax_t{64} << 20;
/// Most rows an IB2d structure file may hold.
inline constexpr std::size_t kMaxIb2dRows = 2'000'000;

/// Reads the structure at `stem`: STEM.vertex is required, the other files are optional (a missing
/// one gives an empty list). Strict: every file must be a regular file of at most kMaxIb2dFileBytes;
/// line 1 a single non-negative integer count of at most kMaxIb2dRows that equals the number of
/// rows; blank lines only at the end; every row the file's column count (a .spring file 4 or 5, the
/// same in every row) of finite numbers; point indices integers in [1, vertex count], the points of
/// a spring or beam distinct; stiffnesses, rest lengths and damping >= 0; alpha in [1, 10].
/// Numbers are read locale-independently (std::from_chars: "1", "1.0", "6.5536e+10", "-7.311e-04").
/// Any violation throws InputError naming the file and, where one applies, the line (1-based),
/// the column and what was expected.
elastic::Ib2dStructure read_ib2d_structure(const std::filesystem::path& stem);
/// The files of the structure at `stem` that are there (those read_ib2d_structure reads), in the
/// order .vertex, .spring, .d_spring, .beam, .nonInv_beam, .target.
std::vector<std::filesystem::path> ib2d_files_present(const std::filesystem::path& stem);

/// Writes STEM.vertex and each other file whose list is non-empty, each atomically
/// (write_file_atomically), numbers as the shortest text that reads back to the same double, so
/// read_ib2d_structure(stem) returns `s` bit for bit. A .spring file gets the alpha column only
/// when some spring's alpha is not 1. An optional file of the stem whose list is empty is removed
/// when one is there (it would otherwise be read back). Before anything is written the structure is
/// checked against the reader's rules, plus: a spring's damping must be 0 and a damped spring's
/// alpha 1 (their files have no column for them); a violation throws InputError, a failed write
/// RunError.
void write_ib2d_structure(const elastic::Ib2dStructure& s, const std::filesystem::path& stem);

}  // namespace jellysim::io
