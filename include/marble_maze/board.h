// The tilting board: roll about x and pitch about y around a pivot at the centre of the floor's
// top surface, driven by target angles or by tilt rates, within a tilt and a tilt-rate limit.
#pragma once

#include <array>

#include "marble_maze/bytes.h"
#include "marble_maze/geometry.h"
#include "marble_maze/params.h"
#include "marble_maze/rotation.h"

namespace marble_maze {

class Board {
 public:
  explicit Board(const Params& params);

  /// Back to the given tilt, at rest.
  void reset(double roll, double pitch);
  /// New tilt limit, rate limit and response time; targets beyond the new limit are brought
  /// within it, and the board moves there as it moves to any target.
  void setLimits(const Params& params);
  /// Drive towards target angles (clamped to the tilt limit) like a servo: a first-order lag with
  /// the response time, at up to the tilt-rate limit. Returns whether the drive changed (false:
  /// the targets in force, to the last bit).
  bool setTargetTilt(double roll, double pitch);
  /// Drive at the given rates (clamped to the tilt-rate limit) until the tilt limit stops them.
  /// Returns whether the drive changed (false: the rates in force, to the last bit).
  bool setTiltRate(double roll_rate, double pitch_rate);
  /// Moves the board over a step of h seconds, turning each angle by at most `most_turn` (rad),
  /// and updates its angular velocity.
  void advance(double h, double most_turn = 1e9);

  double roll() const { return roll_; }
  double pitch() const { return pitch_; }
  /// Rotation from the board frame to the world frame: R = Ry(pitch) Rx(roll) (REP 103, no yaw).
  const Mat3& rotation() const { return rotation_; }
  /// The constant angular velocity (world frame) that carried the board over the last step.
  const Vec3& angularVelocity() const { return angular_velocity_; }

  /// R = Ry(pitch) Rx(roll). (Inline, always: a matrix returned through memory, written a number
  /// at a time, is read back in pairs by the next product, which then waits for the writes to
  /// land; and a third caller, restore, made GCC call it out of line from advance, 20 more
  /// instructions a step.)
  [[gnu::always_inline]] static Mat3 rotationFor(double roll, double pitch) {
    CosSinc cs_r, cs_p;
    cosSinc(roll * roll, pitch * pitch, &cs_r, &cs_p);
    const double cr = cs_r.cos, sr = roll * cs_r.sinc;
    const double cp = cs_p.cos, sp = pitch * cs_p.sinc;
    Mat3 r;                     // Ry(pitch) * Rx(roll), multiplied out
    r << cp, sp * sr, sp * cr,  //
        0, cr, -sr,             //
        -sp, cp * sr, cp * cr;
    return r;
  }

  /// Everything that changes as the board moves (not its limits), bit for bit.
  void save(ByteWriter* out) const;
  /// Back to a saved state, which then moves under this board's limits and servo (targets and
  /// rates brought within them). Throws std::runtime_error naming a value no board has (a drive
  /// of neither kind, a value not finite, an angle beyond a quarter turn, a rotation not its
  /// angles'), changing nothing then.
  void restore(ByteReader* in);

 private:
  enum class Drive { Target, Rate };

  /// A value save() writes after the drive, by name (for restore's messages).
  struct SavedValue {
    const char* name;
    double Board::*member;
  };
  static const std::array<SavedValue, 8>& savedValues();
  /// Targets and rates within the limits.
  void keepWithinLimits();
  /// The fraction of the way to its target the servo covers in h seconds (its first-order lag).
  double approachOver(double h) const;
  double clampTilt(double angle) const;
  double clampRate(double rate) const;

  double tilt_limit_ = 0;
  double tilt_rate_limit_ = 0;  // 0 = unlimited
  double response_time_ = 0;    // 0 = reaches a target at once (within the rate limit)
  double approach_step_ = 0;    // the step the lag's approach_ was worked out for
  double approach_ = 1;         // fraction of the way to the target covered in one step
  Drive drive_ = Drive::Target;
  double target_roll_ = 0, target_pitch_ = 0;
  double roll_rate_ = 0, pitch_rate_ = 0;
  double roll_ = 0, pitch_ = 0;
  Mat3 rotation_ = Mat3::Identity();
  Vec3 angular_velocity_ = Vec3::Zero();
};

}  // namespace marble_maze
