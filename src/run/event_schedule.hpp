// The times a run must land on: the output times, each probe's sample times, the run's periodic call
// and the run's end. A run shortens its step to end at the earliest of them (next_time()), then fires
// what the new time has reached.
//
// One tolerance decides "reached" for every event: the time is at most kTolerance of the event's
// interval before it (interval: the stream's `every`, or the run's duration). A step shortened to end
// on an event lands on it exactly (t + (e - t) == e for t and e within a factor 2 of each other), so the
// tolerance only matters for a step that the time step limit happened to end a hair short of an event:
// that round-off counts as the event, instead of costing one more step of a nanosecond. Events closer
// together than that are reached by one step, and each fires once.
#pragma once

#include <limits>
#include <vector>

namespace seismpm {

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

class EventSchedule {
 public:
  static constexpr double kTolerance = 1e-9;  // relative to the interval of the event's stream

  // How a stream counts its times. Each is the arithmetic that placed the files and samples before the
  // schedule existed, kept so that the steps land where they always did (a time one bit off changes
  // the last step before it, and every result after).
  enum class Spacing {
    Running,    // anchor, anchor + every, (anchor + every) + every, ...: a running sum (output files)
    Multiples,  // k every, the first one after the last firing (probe samples); every = 0: every step
    FromStart,  // anchor + n every, n = 1, 2, ... (a run's periodic call; the run starts at the anchor)
  };
  using Stream = int;

  // A stream of events `every` s apart (> 0; Multiples also 0) counted from `anchor`. Its first event
  // is the anchor itself (Running, Multiples) or one interval after it (FromStart).
  Stream add(Spacing spacing, double every, double anchor);
  void remove(Stream s);
  double every(Stream s) const { return at(s).every; }
  double next_time(Stream s) const { return at(s).next; }
  // True when time t has reached the stream's next event (always, for Multiples with every = 0).
  bool reached(Stream s, double t) const;
  // The stream fired at t (reached or not: a write or a sample forced at a run's end counts too): its
  // next event is its first one that t has not reached.
  void fired(Stream s, double t);

  // The run's end at start + duration (duration may be infinite: a run of a number of steps).
  void begin_run(double start, double duration);
  void end_run();
  double run_end() const { return end_; }
  bool run_over(double t) const { return reached(end_, t, duration_); }

  // The earliest pending event of all streams and the run's end: where the next step must stop.
  double next_time() const;

  // The rule itself: time t has reached an event at `event` of a stream `interval` s apart.
  static bool reached(double event, double t, double interval) { return event - t <= tolerance(interval); }
  static double tolerance(double interval) {
    return interval < std::numeric_limits<double>::infinity() ? kTolerance * interval : 0.0;
  }

 private:
  template <int>
  friend class CheckpointAccess;
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  struct Entry {
    Spacing spacing;
    double every, anchor, next;
    long count;  // FromStart: the events fired so far
    bool active;
  };
  const Entry& at(Stream s) const;
  std::vector<Entry> streams_;
  double end_ = kInfinity, duration_ = kInfinity;
};

}  // namespace seismpm
