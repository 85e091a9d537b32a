// Fuzzes a session's restore from a snapshot, as a bag's `snapshot` topic hands it over
// (resimulate --bag, the replay node). An input is either a list of edits to a sound snapshot (a
// session on the classic maze, mid-play with two commands queued): each three bytes, a 16-bit
// offset into it and the byte to put there, so that every value of the state is reached; or,
// behind a first byte 0xFF, the snapshot's bytes themselves (fuzz/corpus/snapshot/raw_sound_v3
// is one, raw_sound one of version 2, for libFuzzer to grow and cut). A snapshot is either refused
// with a std::runtime_error that says "snapshot: ..." (the session unchanged), or it is a state
// that restores again to the bit from its own save, and that the session steps on for 30 steps
// under a tilt, staying sound (the marble and the board finite, the orientation of unit length, the
// tilt within a quarter turn), as does a session of another servo and lower limits that restores
// it. Anything else (another exception, a crash, undefined behaviour, a hang) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "marble_maze/embedded_mazes.h"
#include "marble_maze/maze_file.h"
#include "marble_maze/session.h"

namespace mm = marble_maze;

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

mm::Scene classic() {
  return mm::parseScene(mm::embeddedMazes().front().second, "classic.yaml");
}

/// The classic maze under another servo and lower limits (a replay with other physics).
mm::Scene otherPhysics() {
  mm::Scene scene = classic();
  scene.params.tilt_response_time = 0.01;
  scene.params.tilt_limit = 0.05;
  scene.params.tilt_rate_limit = 0.5;
  return scene;
}

/// A sound snapshot to edit: mid-play, the board moving, two commands queued.
const std::vector<std::uint8_t>& soundSnapshot() {
  static const std::vector<std::uint8_t> saved = [] {
    mm::Session s(classic());
    s.command({1, mm::TiltCommand::Kind::Angles, 0.08, -0.05});
    s.command({400, mm::TiltCommand::Kind::Rates, -0.3, 0.2});
    s.command({500, mm::TiltCommand::Kind::Angles, 0, 0.1});
    s.run(150);
    mm::Session again(classic());
    again.restore(s.save());
    check(again.save() == s.save());  // (else every edit would be refused, and nothing fuzzed)
    return s.save();
  }();
  return saved;
}

bool sound(const mm::Session& s) {
  const mm::Marble& m = s.simulation().marble();
  const mm::Board& b = s.simulation().board();
  return m.position.allFinite() && m.velocity.allFinite() && m.angular_velocity.allFinite() &&
         std::abs(m.orientation.squaredNorm() - 1) < 1e-6 && b.rotation().allFinite() &&
         b.angularVelocity().allFinite() && std::abs(b.roll()) <= mm::kQuarterTurn &&
         std::abs(b.pitch()) <= mm::kQuarterTurn;
}

/// Steps a session that has just restored a snapshot, checking it stays sound.
void stepOn(mm::Session* session) {
  check(sound(*session));
  for (int k = 0; k < 30; ++k) {
    session->command({session->steps(), mm::TiltCommand::Kind::Angles, 0.1, -0.05});
    session->run(1);
    check(sound(*session));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static mm::Session session(classic());
  static mm::Session other(otherPhysics());
  std::vector<std::uint8_t> bytes;
  if (size > 0 && data[0] == 0xFF) {
    bytes.assign(data + 1, data + size);
  } else {
    bytes = soundSnapshot();
    for (std::size_t k = 0; k + 3 <= size; k += 3)
      bytes[(data[k] | data[k + 1] << 8) % bytes.size()] = data[k + 2];
  }
  const std::vector<std::uint8_t> before = session.save();
  try {
    session.restore(bytes);
  } catch (const std::runtime_error& e) {
    check(std::string(e.what()).rfind("snapshot: ", 0) == 0);  // it says what was wrong
    check(session.save() == before);                           // and changed nothing
    return 0;
  }
  mm::Session again = session;
  again.restore(session.save());
  check(again.save() == session.save());  // a restored state restores again to the bit
  other.restore(bytes);  // (what one session takes, another of the same maze takes)
  stepOn(&session);
  stepOn(&other);
  return 0;
}
