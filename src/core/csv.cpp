#include "marble_maze/csv.h"

#include <algorithm>
#include <charconv>
#include <cstring>

#include "marble_maze/exact_text.h"

namespace marble_maze {

const char kTrajectoryColumns[] = "t,x,y,z,vx,vy,vz,wx,wy,wz,roll,pitch,contacts,phase\n";
const char kEventColumns[] = "t,kind,i,j,k,speed\n";

const char* phaseName(MarblePhase phase) {
  switch (phase) {
    case MarblePhase::Free:
      return "free";
    case MarblePhase::InHole:
      return "in_hole";
    case MarblePhase::AtGoal:
      return "at_goal";
    case MarblePhase::OffBoard:
      return "off_board";
  }
  return "unknown";
}

void appendTrajectoryRow(std::string* out, const Simulation& sim) {
  // (The whole row is written into a buffer on the stack and appended at once: a row a step
  // must cost little beside the step.)
  const Marble& m = sim.marble();
  const Vec3 position = sim.worldPosition();
  char row[16 * kExactTextSize];
  char* end = writeExact(row, sim.time());
  for (const Vec3* v : {&position, &m.velocity, &m.angular_velocity})
    for (int a = 0; a < 3; ++a) {
      *end++ = ',';
      end = writeExact(end, (*v)[a]);
    }
  for (const double angle : {sim.board().roll(), sim.board().pitch()}) {
    *end++ = ',';
    end = writeExact(end, angle);
  }
  *end++ = ',';
  end = std::to_chars(end, end + kExactTextSize, m.contacts).ptr;
  *end++ = ',';
  const char* phase = phaseName(m.phase);
  end = std::copy(phase, phase + std::strlen(phase), end);
  *end++ = '\n';
  out->append(row, end);
}

void appendEventRow(std::string* out, const Event& event) {
  appendExact(out, event.time);
  *out += ',' + toString(event.kind) + ',' + std::to_string(event.tile.x()) + ',' +
          std::to_string(event.tile.y()) + ',' + std::to_string(event.tile.z()) + ',';
  appendExact(out, event.speed);
  *out += '\n';
}

}  // namespace marble_maze
