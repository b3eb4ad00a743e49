// core::StateArchive (issue 23): what one archive() function saves it restores bit for bit, and a
// checkpoint that does not fit the simulation is refused with the entry named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "jellysim/core/state_archive.hpp"

namespace jellysim::core {
namespace {

/// A stateful class as the simulation's are: one function for both directions.
struct Stateful {
  double time = 0.0;
  long steps = 0;
  bool started = false;
  std::vector<double> field = std::vector<double>(4, 0.0);  // fixed by the "grid"
  std::vector<int> history;                                   // its length is state
  std::vector<std::vector<double>> frames;
  std::string note;

  void archive(StateArchive& a) {
    const StateArchive::Scope scope(a, "thing");
    a.value("time", time);
    a.value("steps", steps);
    a.value("started", started);
    a.values("field", std::span(field));
    a.vector("history", history);
    a.nested("frames", frames);
    a.text("note", note);
  }
};

Stateful example() {
  Stateful s;
  s.time = 0.1 + 0.2;  // not a short decimal: restored by its bits
  s.steps = 1234567890123;
  s.started = true;
  s.field = {1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::infinity()};
  s.history = {3, 1, 4, 1, 5};
  s.frames = {{1.0, 2.0}, {}, {3.0}};
  s.note = std::string("ended at t = 0.3 s\0with a nul", 29);
  return s;
}

TEST(StateArchive, WhatIsSavedIsRestoredBitForBit) {
  Stateful original = example();
  StateArchive saved = StateArchive::saving();
  original.archive(saved);
  StateArchive restoring = StateArchive::restoring(saved.take_entries());
  Stateful copy;
  copy.archive(restoring);
  restoring.check_all_read();
  EXPECT_EQ(std::memcmp(&copy.time, &original.time, sizeof(double)), 0);
  EXPECT_EQ(copy.steps, original.steps);
  EXPECT_TRUE(copy.started);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(std::memcmp(&copy.field[k], &original.field[k], sizeof(double)), 0) << k;
  EXPECT_TRUE(std::signbit(copy.field[1]));
  EXPECT_EQ(copy.history, original.history);
  EXPECT_EQ(copy.frames, original.frames);
  EXPECT_EQ(copy.note, original.note);
}

TEST(StateArchive, AnotherSimulationsCheckpointIsAMismatchNamingTheEntry) {
  Stateful original = example();
  StateArchive saved = StateArchive::saving();
  original.archive(saved);
  const StateArchive::Entries entries = saved.take_entries();

  // A field on another grid.
  Stateful bigger;
  bigger.field.assign(6, 0.0);
  StateArchive a = StateArchive::restoring(entries);
  try {
    bigger.archive(a);
    FAIL() << "a field of another size was restored";
  } catch (const StateMismatch& e) {
    EXPECT_NE(std::string(e.what()).find("'thing.field' has 4 values where this simulation has 6"), std::string::npos)
        << e.what();
  }
  // An entry the simulation does not have, and one it has that the checkpoint lacks.
  StateArchive::Entries extra = entries;
  extra["thing.tracers"] = "";
  StateArchive b = StateArchive::restoring(extra);
  Stateful copy;
  copy.archive(b);
  EXPECT_THROW(b.check_all_read(), StateMismatch);
  StateArchive::Entries missing = entries;
  missing.erase("thing.note");
  StateArchive c = StateArchive::restoring(missing);
  EXPECT_THROW(copy.archive(c), StateMismatch);
}

TEST(StateArchive, AnEntrySavedTwiceIsAProgrammingError) {
  StateArchive a = StateArchive::saving();
  double x = 1.0;
  a.value("x", x);
  EXPECT_THROW(a.value("x", x), std::logic_error);
}

}  // namespace
}  // namespace jellysim::core
