// The world: a marble on a tilting tile-grid board, advanced in fixed steps.
#pragma once

#include <cstdint>
#include <vector>

#include "marble_maze/board.h"
#include "marble_maze/collision.h"
#include "marble_maze/contact_solver.h"
#include "marble_maze/events.h"
#include "marble_maze/integrator.h"
#include "marble_maze/maze_file.h"

namespace marble_maze {

/// Free, or held where the game ended for it.
enum class MarblePhase { Free, InHole, AtGoal, OffBoard };

struct Marble {
  /// m, the centre, along the world's axes from the board's pivot: the physics is worked out
  /// around the board wherever it is, the same to the last bit (Simulation::worldPosition()
  /// adds where the board is).
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();          ///< m/s, world frame
  Vec3 angular_velocity = Vec3::Zero();  ///< rad/s, world frame
  Quat orientation = Quat::Identity();   ///< world frame
  MarblePhase phase = MarblePhase::Free;
  /// Surfaces touched (coplanar tiles count once) when last looked at in the last step: at the
  /// start of its last substep, or at the last impact within it. (A look after the move would
  /// cost a contact query a step; the next step's first look is that one.)
  int contacts = 0;
};

/// Everything of a simulation that changes as it runs, and nothing else: with the same scene,
/// restoring it continues the run bit for bit.
struct SimulationState {
  Marble marble;
  Board board;
  Vec3 held_in_grid = Vec3::Zero();
  double time = 0;
  std::uint64_t steps = 0;
};

/// What the steps have cost, counted rather than timed (a machine's speed cannot move a count):
/// the substeps taken, the swept tests run and the solid tiles those looked at, and how often the
/// tiles near the marble were gathered from the grid.
struct StepCounts {
  std::uint64_t substeps = 0;
  std::uint64_t sweeps = 0;
  std::uint64_t tiles_swept = 0;
  std::uint64_t sweeps_clear = 0;  ///< sweeps answered by the near tiles, without a walk
  std::uint64_t gathers = 0;       ///< times the near tiles were gathered anew from the grid
  PairSolveCounts pairs;           ///< the contact solver's pairs: Newton's method and its steps
};

/// A marble on a tilting board: the engine, a step at a time. Deterministic: the same scene and
/// inputs give bit-identical states; nothing depends on wall time, addresses or threads.
///
/// A step is taken in substeps, each as its stages: the board moves (moveBoard), the contacts
/// at its start are gathered (gatherContacts) and a kick at the start resolved (impact), the
/// integrator's path is swept to the next impact, resolved, and on (integrateToImpacts), and a
/// marble low over a hole, the goal or nothing is held there (checkFinish). The commands that
/// set the tilt come before a step, from Session.
///
/// To drive a simulation, use Session (session.h): tilt commands through its queue, the tilt and
/// rate timeouts, the auto reset, pause, place, load and snapshots, as the node, the runner and
/// the replay drive it. Simulation's own setters (setTargetTilt, setTiltRate, placeMarble) are
/// the lower-level access beneath it, for the engine's tests, the benchmark and the trade sweep.
///
/// Frames: the world's z points up (REP 103) and gravity along -z. The board frame has its origin
/// at the pivot (the centre of the floor's top surface), which stays at the world's origin, and
/// turns with the board; the grid frame is the board frame moved to the grid's corner.
class Simulation {
 public:
  /// Throws ParamError when the scene's parameters are inconsistent.
  explicit Simulation(const Scene& scene);

  /// New physics from the next step on, the state kept (a tilt beyond a new limit is brought
  /// within it). Throws ParamError, changing nothing, when they are inconsistent, or when the
  /// time is 2^50 of the new steps or more (a step too short to time it closely).
  void setParams(const Params& params);
  SimulationState state() const;
  /// Throws ParamError, changing nothing, when the state's time is 2^50 steps or more.
  void restore(const SimulationState& state);
  /// The state as bytes, bit for bit (the scene, maze and physics, is not in them).
  void save(ByteWriter* out) const;
  /// `with_origin`: the state was saved with the time and steps its time counts from (a session
  /// snapshot of version 2 on). Throws std::runtime_error naming a value no simulation saves
  /// (the marble's or the board's: not finite, out of range), changing nothing.
  void restore(ByteReader* in, bool with_origin = true);
  /// Why the marble cannot be placed at a board-frame position (inside a tile, off the board),
  /// or "" when it can.
  std::string whyNotPlaceable(const Vec3& position_in_board) const;

  /// The marble back to its start, at rest; the board back to its initial tilt, at rest.
  void reset();
  void setTargetTilt(double roll, double pitch) {
    if (board_.setTargetTilt(roll, pitch)) resting_ = false;
  }
  void setTiltRate(double roll_rate, double pitch_rate) {
    if (board_.setTiltRate(roll_rate, pitch_rate)) resting_ = false;
  }
  /// Puts the marble, free, at a board-frame position with a world-frame velocity and spin.
  void placeMarble(const Vec3& position_in_board, const Vec3& velocity,
                   const Vec3& angular_velocity = Vec3::Zero());
  /// Advances one fixed step of params().step seconds (params().substeps substeps). A step that
  /// left the marble and the board as they were, to the last bit and with no event, is a fixed
  /// point: until something changes them (a new tilt or rate, a place, reset, restore or new
  /// physics) the steps after it only count the time, as Box2D's bodies sleep, and give what
  /// stepping would to the last bit.
  void step();
  /// Whether the marble and the board rest: the last step changed nothing (see step()).
  bool resting() const { return resting_; }

  const Maze& maze() const { return maze_; }
  const Params& params() const { return params_; }
  const Board& board() const { return board_; }
  const Marble& marble() const { return marble_; }
  /// s: the steps taken, each as long as it was: the time at the last change of parameters (or
  /// load) plus the steps since times the step, not a sum, which drifts by its roundings (1e-13 s
  /// over 10 s of 1 ms steps)
  double time() const { return time_; }
  std::uint64_t steps() const { return steps_; }
  /// The events of the last step, in order.
  const std::vector<Event>& events() const { return events_; }
  /// The tile grid's placement in the world now.
  GridFrame gridFrame() const;
  /// The marble's centre in the board frame.
  Vec3 marbleInBoard() const;
  /// The marble's centre in the world: its position plus where the board's pivot is.
  Vec3 worldPosition() const { return marble_.position + params_.board_position; }
  /// Kinetic plus potential energy (J), potential measured from the world's z = 0, both at the
  /// instant the integrator's velocity belongs to (for semi-implicit Euler half a substep back).
  double energy() const;
  /// The work (J) the moving board has done on the marble through its contacts since the marble
  /// was last placed (reset, place or restore): its energy never rises above the energy it was
  /// placed with plus this. Taken once a stretch, so approximate at coarse steps where a scheme
  /// samples the contacts more than once (velocity Verlet, RK4).
  double boardWork() const { return board_work_; }
  /// The marble's start position in the board frame.
  Vec3 startInBoard() const;
  /// The cost of the steps since the simulation was made (not part of its state).
  StepCounts counts() const {
    StepCounts counts = counts_;
    counts.gathers = near_.gathers;  // counted where the tiles are gathered
    // (Those of the solvers setParams replaced are in counts_.)
    counts.pairs += solver_.pairCounts();
    return counts;
  }

 private:
  /// The marble's dynamics against the contacts of the moment, as the integrators sample them.
  class ContactDynamics : public Dynamics {
   public:
    explicit ContactDynamics(Simulation* sim) : sim_(sim) {}
    Velocities after(const Velocities& start, double duration, const Sample& at) override;
    bool constantForces() const override { return !turning_ && sim_->forces_.constant(); }
    /// From here on the velocities are taken in the frame of a board turning at `spin` (world
    /// axes as they were when the marble was at `start`, from the pivot), where the contacts
    /// stand still: the marble feels gravity turning back with the board, and the Coriolis and
    /// centrifugal forces. Only for a marble on contacts (in flight the world's parabola is
    /// exact).
    void followTurn(const Vec3& start, const Vec3& spin);

   private:
    Velocities afterInBoardFrame(const Velocities& start, double duration, const Sample& at);

    Simulation* sim_;
    bool sampled_ = false;
    bool turning_ = false;
    Vec3 start_ = Vec3::Zero(), spin_ = Vec3::Zero(), axis_ = Vec3::Zero();
    double rate_ = 0;  // rad/s, |spin_|
  };

  /// The board's motion over a substep, as the stages after it take it.
  struct BoardMotion {
    GridFrame start;     ///< the pose at the substep's start, turning at the substep's rate
    Vec3 previous_spin;  ///< the board's angular velocity over the substep before
    double start_roll, start_pitch;
  };

  /// How many substeps this step takes: the params' count, or more where the board turns far
  /// or air drag slows the marble fast.
  int substepsFor() const;
  /// The step's substeps.
  void takeSubsteps();
  /// The step's substeps, and whether they left the marble and the board as they were, to the
  /// last bit, with no event.
  bool substepsChangeNothing();
  /// One substep, as its stages: the board, the contacts, a kick at the start, the contacts'
  /// pose, integrate to the next impact and the impacts, the marble's turn, the finish.
  void substep(double h, double start_time);
  BoardMotion moveBoard(double h);
  /// A finished marble rides along with the board.
  void rideWithBoard();
  void gatherContacts(const GridFrame& start, double h);
  void pushOut();
  /// The contacts' normals and surface velocities in the pose where the scheme's forces act.
  void turnContactsToForcePose(const BoardMotion& motion, double h);
  /// The substep after its start's impacts, the contacts' normals and surface velocities those
  /// of the board's pose they push in until the first impact (or, `in_board_frame`, the
  /// start's, the stretch to the first impact taken in the turning board's frame); each impact
  /// resolved in turn.
  void integrateToImpacts(double h, double start_time, const BoardMotion& motion,
                          bool in_board_frame);
  void turnMarble(double h);
  /// The contacts that act over a stretch (acting()): all but those the marble is leaving.
  void chooseActingContacts(double duration, const Vec3& previous_spin);
  /// Whether the marble moves along every contact, neither approaching nor leaving it.
  bool restsOnContacts() const;
  /// `in_board_frame`: the path is relative to the board, where its surfaces stand still.
  void keepOutOfContacts(Trajectory* trajectory, double duration, bool in_board_frame) const;
  /// The velocity of the surface under a contact where the marble is now, as the board moves
  /// over the substep (a contact's own is where the scheme holds the marble to it).
  Vec3 startSurfaceVelocity(const Contact& c) const {
    return frame_.surfaceVelocity(marble_.position - params_.marble_radius * c.normal);
  }
  void keepOnHeldContacts(Sweep* sweep) const;
  /// Where and when (`fraction` of the substep) a path swept against a turning board truly
  /// meets the face it hit (the sweep's `met` for another tile, or a still board).
  Vec3 meetTurningFace(const Trajectory& path, const BoardMotion& motion, const Contact& face,
                       double* fraction, const Vec3& met) const;
  void impact(double time);
  void checkFinish(double time);
  void hold(MarblePhase phase, EventKind kind, const Index3& tile, double time);

  Maze maze_;
  Params params_;
  Board board_;
  ContactSolver solver_;
  FieldForces forces_;
  const Integrator* integrator_;  // stateless, shared
  double mass_, inertia_;         // of the marble: params_'s, worked out once
  double most_turn_;              // rad: the most the board turns in a substep (mostTurnFor)
  Marble marble_;
  GridFrame frame_;
  Vec3 held_in_grid_ = Vec3::Zero();  // where a finished marble rests, in the grid frame
  double time_ = 0;
  // The time and the steps when the step length last changed (or the state was restored): the
  // time now is the time then plus the steps since times the step.
  double time_origin_ = 0;
  std::uint64_t steps_origin_ = 0;
  double board_work_ = 0;
  std::uint64_t steps_ = 0;
  bool resting_ = false;  // the last step changed nothing, and nothing has since
  StepCounts counts_;
  std::vector<Event> events_;
  std::vector<Contact> contacts_;         // reused: no allocation per step
  NearTiles near_;                        // around the marble at the substep's start
  std::vector<ContactOutcome> outcomes_;  // of the last impact
  // The contacts whose forces act over the current stretch, and what they did in its first
  // sample; a bent path leaves out the contacts it is leaving (faster than resting and than the
  // surface under it changes; it may come back to them: an impact then, found by the sweep).
  // (All of contacts_, most often, or those of them copied to some_acting_.)
  const std::vector<Contact>& acting() const { return all_act_ ? contacts_ : some_acting_; }
  bool all_act_ = true;
  std::vector<Contact> some_acting_;
  double substep_ = 0;  // s: the last step's substep (shorter when the step was cut)
  std::vector<ContactOutcome> acting_outcomes_, sample_outcomes_;
};

}  // namespace marble_maze
