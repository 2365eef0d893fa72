#include "event_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"

namespace seismpm {

namespace {

// A probe sampled off its times (at the end of a run) less than this fraction of its interval before
// one of them has taken that time's sample: the next one is the time after, not a step of a few
// nanoseconds later. (This is how probes have always counted; it is not a landing tolerance.)
constexpr double kOffTimeSample = 1e-6;

}  // namespace

EventSchedule::Stream EventSchedule::add(Spacing spacing, double every, double anchor) {
  const bool valid = spacing == Spacing::Multiples ? every >= 0.0 : every > 0.0;
  if (!valid || !std::isfinite(every) || !std::isfinite(anchor))
    throw InputError("event schedule: an interval must be finite and > 0 (>= 0 for samples), got " +
                     std::to_string(every));
  Entry e{spacing, every, anchor, anchor, 0, true};
  if (spacing == Spacing::FromStart) e.next = anchor + every;
  if (spacing == Spacing::Multiples && every == 0.0) e.next = kInfinity;  // every step: nothing to land on
  // Reuse a removed stream's slot: a script that runs in many chunks adds a call stream per run.
  const auto free = std::find_if(streams_.begin(), streams_.end(), [](const Entry& x) { return !x.active; });
  if (free != streams_.end()) {
    *free = e;
    return static_cast<Stream>(free - streams_.begin());
  }
  streams_.push_back(e);
  return static_cast<Stream>(streams_.size() - 1);
}

void EventSchedule::remove(Stream s) {
  at(s);
  streams_[s].active = false;
}

const EventSchedule::Entry& EventSchedule::at(Stream s) const {
  if (s < 0 || s >= static_cast<Stream>(streams_.size()) || !streams_[s].active)
    throw std::out_of_range("event schedule: no stream " + std::to_string(s));
  return streams_[s];
}

bool EventSchedule::reached(Stream s, double t) const {
  const Entry& e = at(s);
  if (e.spacing == Spacing::Multiples && e.every == 0.0) return true;
  return reached(e.next, t, e.every);
}

void EventSchedule::fired(Stream s, double t) {
  at(s);
  Entry& e = streams_[s];
  switch (e.spacing) {
    case Spacing::Running:
      while (reached(e.next, t, e.every)) e.next += e.every;
      break;
    case Spacing::Multiples:
      if (e.every > 0.0) e.next = (std::floor(t / e.every + kOffTimeSample) + 1.0) * e.every;
      break;
    case Spacing::FromStart:
      while (reached(e.anchor + double(e.count + 1) * e.every, t, e.every)) ++e.count;
      e.next = e.anchor + double(e.count + 1) * e.every;
      break;
  }
}

void EventSchedule::begin_run(double start, double duration) {
  if (!(duration >= 0.0)) throw InputError("run: duration must be >= 0");
  end_ = start + duration;
  duration_ = duration;
}

void EventSchedule::end_run() {
  end_ = kInfinity;
  duration_ = kInfinity;
}

double EventSchedule::next_time() const {
  double next = end_;
  for (const Entry& e : streams_)
    if (e.active) next = std::min(next, e.next);
  return next;
}

}  // namespace seismpm
