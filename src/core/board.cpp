#include "marble_maze/board.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "marble_maze/rotation.h"

namespace marble_maze {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

}  // namespace

Board::Board(const Params& params) {
  setLimits(params);
  reset(params.initial_roll, params.initial_pitch);
}

void Board::setLimits(const Params& params) {
  tilt_limit_ = params.tilt_limit;
  tilt_rate_limit_ = params.tilt_rate_limit;
  response_time_ = params.tilt_response_time;
  approach_step_ = 0;  // the lag's step fraction is worked out again
  keepWithinLimits();
}

void Board::keepWithinLimits() {
  target_roll_ = clampTilt(target_roll_);
  target_pitch_ = clampTilt(target_pitch_);
  roll_rate_ = clampRate(roll_rate_);
  pitch_rate_ = clampRate(pitch_rate_);
}

const std::array<Board::SavedValue, 8>& Board::savedValues() {
  static const std::array<SavedValue, 8> values = {{{"servo step", &Board::approach_step_},
                                                    {"servo approach", &Board::approach_},
                                                    {"target roll", &Board::target_roll_},
                                                    {"target pitch", &Board::target_pitch_},
                                                    {"roll rate", &Board::roll_rate_},
                                                    {"pitch rate", &Board::pitch_rate_},
                                                    {"roll", &Board::roll_},
                                                    {"pitch", &Board::pitch_}}};
  return values;
}

void Board::save(ByteWriter* out) const {
  out->put(static_cast<std::int32_t>(drive_));
  for (const SavedValue& v : savedValues()) out->put(this->*v.member);
  out->put(rotation_);
  out->put(angular_velocity_);
}

void Board::restore(ByteReader* in) {
  Board next = *this;  // (this board changes only once all of the state is read and sound)
  const auto refuse = [](const std::string& why) {
    throw std::runtime_error("snapshot: the board's " + why);
  };
  const auto drive = in->get<std::int32_t>();
  if (drive != static_cast<std::int32_t>(Drive::Target) &&
      drive != static_cast<std::int32_t>(Drive::Rate))
    refuse("drive " + std::to_string(drive) + " is neither a target (0) nor rates (1)");
  next.drive_ = static_cast<Drive>(drive);
  for (const SavedValue& v : savedValues()) {
    next.*v.member = in->get<double>();
    if (!std::isfinite(next.*v.member)) refuse(std::string(v.name) + " is not finite");
  }
  for (const auto& [name, angle] : {std::pair{"roll", next.roll_}, {"pitch", next.pitch_}})
    if (!(std::abs(angle) <= kQuarterTurn))
      refuse(std::string(name) + " " + exactText(angle) + " rad is beyond a quarter turn");
  // The rotation is always its angles' (reset and advance set them together), taken anew here:
  // the same to the bit, and the same to rounding as a build whose rotationFor rounded otherwise
  // saved it (an older bag's). A rotation further from them is not a board's state.
  const Mat3 saved_rotation = in->mat3();
  next.rotation_ = rotationFor(next.roll_, next.pitch_);
  if (!((saved_rotation - next.rotation_).cwiseAbs().maxCoeff() <= 1e-12))
    refuse("rotation is not that of its roll and pitch");
  next.angular_velocity_ = in->vec3();
  if (!next.angular_velocity_.allFinite()) refuse("angular velocity is not finite");
  // Saved under other limits or another servo (a replay with other physics), it moves under
  // this board's: its targets and rates within them, its servo's approach over the saved step
  // worked out anew (the same to the bit under the same servo, so the state is unchanged).
  next.keepWithinLimits();
  if (next.approach_step_ > 0) next.approach_ = next.approachOver(next.approach_step_);
  *this = next;
}

void Board::reset(double roll, double pitch) {
  roll_ = target_roll_ = clampTilt(roll);
  pitch_ = target_pitch_ = clampTilt(pitch);
  roll_rate_ = pitch_rate_ = 0;
  drive_ = Drive::Target;
  rotation_ = rotationFor(roll_, pitch_);
  angular_velocity_.setZero();
}

double Board::approachOver(double h) const {
  return response_time_ > 0 ? 1.0 - std::exp(-h / response_time_) : 1.0;
}

double Board::clampTilt(double angle) const {
  return std::clamp(angle, -tilt_limit_, tilt_limit_);
}

double Board::clampRate(double rate) const {
  return tilt_rate_limit_ > 0 ? std::clamp(rate, -tilt_rate_limit_, tilt_rate_limit_) : rate;
}

bool Board::setTargetTilt(double roll, double pitch) {
  roll = clampTilt(roll);
  pitch = clampTilt(pitch);
  const bool same =
      drive_ == Drive::Target && sameBits(roll, target_roll_) && sameBits(pitch, target_pitch_);
  drive_ = Drive::Target;
  target_roll_ = roll;
  target_pitch_ = pitch;
  return !same;
}

bool Board::setTiltRate(double roll_rate, double pitch_rate) {
  roll_rate = clampRate(roll_rate);
  pitch_rate = clampRate(pitch_rate);
  const bool same =
      drive_ == Drive::Rate && sameBits(roll_rate, roll_rate_) && sameBits(pitch_rate, pitch_rate_);
  drive_ = Drive::Rate;
  roll_rate_ = roll_rate;
  pitch_rate_ = pitch_rate;
  return !same;
}

void Board::advance(double h, double most_turn) {
  double new_roll = roll_, new_pitch = pitch_;
  if (drive_ == Drive::Rate) {
    new_roll = clampTilt(roll_ + roll_rate_ * h);
    new_pitch = clampTilt(pitch_ + pitch_rate_ * h);
  } else {
    // The first-order lag solved exactly over the step, so that any step is stable; a target
    // closer than rounding is taken as reached, so that the board comes to rest.
    if (h != approach_step_) {  // the step is fixed: the exponential is worked out once
      approach_step_ = h;
      approach_ = approachOver(h);
    }
    // (The rate limit bounds the step's turn: no quotient by h and product back, which the
    // next step's angle would wait on.)
    const double most = tilt_rate_limit_ > 0 ? tilt_rate_limit_ * h : kNoLimit;
    const auto follow = [&](double angle, double target) {
      if (std::abs(target - angle) < 1e-12) return target;
      return angle + std::clamp((target - angle) * approach_, -most, most);
    };
    new_roll = follow(roll_, target_roll_);
    new_pitch = follow(pitch_, target_pitch_);
  }
  new_roll = roll_ + std::clamp(new_roll - roll_, -most_turn, most_turn);
  new_pitch = pitch_ + std::clamp(new_pitch - pitch_, -most_turn, most_turn);
  if (new_roll == roll_ && new_pitch == pitch_) {  // at rest: nothing to recompute
    angular_velocity_.setZero();
    return;
  }
  // The angular velocity over the step, in rad/s so that the surface velocity w x (p - pivot)
  // is in m/s: for R = Ry(pitch) Rx(roll), w = pitch' e_y + roll' Ry(pitch) e_x, taken at
  // mid-step.
  const double per_h = 1 / h;
  const double roll_rate = (new_roll - roll_) * per_h, pitch_rate = (new_pitch - pitch_) * per_h;
  const double mid_pitch = 0.5 * (pitch_ + new_pitch);
  const CosSinc mid = cosSinc(mid_pitch * mid_pitch);
  angular_velocity_ = Vec3(roll_rate * mid.cos, pitch_rate, -roll_rate * mid_pitch * mid.sinc);
  roll_ = new_roll;
  pitch_ = new_pitch;
  rotation_ = rotationFor(new_roll, new_pitch);
}

}  // namespace marble_maze
