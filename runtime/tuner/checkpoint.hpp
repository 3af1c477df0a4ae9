// Per-restart checkpoint of the genetic search (JSON): the problem and options it belongs to, the
// generation, the RNG state, the population with its objectives and the restart's front. Written
// after every generation (atomically: temporary file + rename), so a run interrupted at any point
// resumes from the last finished generation and reproduces the uninterrupted run's front.
#pragma once

#include <string>
#include <vector>

#include "tuner/genetic.hpp"

namespace bl::tuner {

struct Checkpoint {
  std::string problem_key, options_key;
  std::uint64_t seed = 0;
  int restart = 0;
  int generation = 0;
  bool complete = false;
  Rng rng;
  std::vector<Genome> population;
  std::vector<Objectives> objectives;
  std::vector<Point> front;
};

void save_checkpoint(const std::string& path, const Checkpoint& c, const Palette& pal);

// Reads `path` into *out when it exists and matches `expect`'s problem key, options key, seed and
// restart; false when there is no file or it belongs to another run (then it is ignored, and
// overwritten by the new run). Throws std::runtime_error naming the file when it is corrupt.
bool load_checkpoint(const std::string& path, const Checkpoint& expect, const Palette& pal, Checkpoint* out);

// Points as JSON (also the MPI driver's wire format): [{"genome": key, "time": t, "error": e}].
std::string points_to_json(const std::vector<Point>& pts);
std::vector<Point> points_from_json(const std::string& text, int palette_size);

}  // namespace bl::tuner
