// A restarted recorder's part of RunMetrics (re-sent statuses, the counts carried over) and the
// reading of the files an earlier recorder of the run wrote (core/record_resume.h).
#include <algorithm>
#include <sstream>
#include <vector>

#include "swarm_transport/core/record_resume.h"
#include "swarm_transport/core/run_metrics.h"

namespace swarm_transport {
namespace core {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text.substr(0, CompleteLength(text)));
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// The data rows of a file whose first line must be `header` (an empty text has none).
bool Rows(const std::string& text, const char* header, const char* name,
          std::vector<std::vector<std::string>>* rows, std::string* error) {
  const std::vector<std::string> lines = Lines(text);
  if (lines.empty()) return true;
  if (lines.front() != header) {
    *error = std::string(name) + " does not start with the recorder's header";
    return false;
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty() || lines[i][0] == kCsvComment) continue;
    rows->push_back(Fields(lines[i]));
  }
  return true;
}

bool ToU64(const std::string& text, std::uint64_t* out) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return false;
  *out = std::stoull(text);
  return true;
}

}  // namespace

std::size_t CompleteLength(const std::string& text) {
  const std::size_t last = text.rfind('\n');
  return last == std::string::npos ? 0 : last + 1;
}

bool ReadEarlierRecord(const std::string& missions_csv, const std::string& run_csv,
                       const std::string& swarm_csv, EarlierRecord* out, std::string* error) {
  EarlierRecord record;
  std::vector<std::vector<std::string>> missions, runs, samples;
  if (!Rows(missions_csv, RunMetrics::kMissionsHeader, "missions.csv", &missions, error) ||
      !Rows(run_csv, RunMetrics::kRunHeader, "run.csv", &runs, error) ||
      !Rows(swarm_csv, RunMetrics::kSwarmHeader, "swarm_count.csv", &samples, error)) {
    return false;
  }
  for (const auto& row : missions) {
    std::uint64_t id = 0;
    if (row.size() < 5 || !ToU64(row[0], &id) || id > 65535) {
      *error = "missions.csv has a row without a mission id in its first column";
      return false;
    }
    record.rows.insert(static_cast<std::uint16_t>(id));
    record.done += row[4] == PhaseName(MissionPhase::kDone) ? 1 : 0;
    record.aborted += row[4] == PhaseName(MissionPhase::kAborted) ? 1 : 0;
  }
  if (!runs.empty() && runs.back().size() >= 7) {
    const auto& run = runs.back();
    std::uint64_t n = 0, ticks = 0;
    if (ToU64(run[5], &n) && n > 0 && !run[6].empty()) {
      record.samples = n;
      record.swarm_count_sum = std::stod(run[6]) * static_cast<double>(n);
    }
    if (ToU64(run[3], &ticks) && ticks > 0) record.last_tick = ticks;
  }
  std::uint64_t tick = 0;
  if (!samples.empty() && !samples.back().empty() && ToU64(samples.back()[0], &tick)) {
    if (!record.last_tick || tick > *record.last_tick) record.last_tick = tick;
  }
  *out = record;
  return true;
}

std::string GapComment(const std::optional<std::uint64_t>& last_tick, const std::string& when) {
  std::string text = std::string(1, kCsvComment) + " gap: the recorder restarted at " + when + "; ";
  text += last_tick ? "nothing recorded after tick " + std::to_string(*last_tick)
                    : "nothing recorded before";
  return text +
         " until the tick below; missions that ended in between follow as recovered "
         "(from their first leaders' re-sent statuses) where a first leader remembers them";
}

std::string ResumedComment(std::uint64_t tick) {
  return std::string(1, kCsvComment) + " gap ends: recording again from tick " +
         std::to_string(tick);
}

std::string RunMetrics::RecoveredComment(std::uint16_t id) {
  return std::string(1, kCsvComment) + " recovered: mission " + std::to_string(id) +
         " was first heard of in a re-sent status after the recorder restarted; its phases "
         "before that status have no ticks and its metrics only the frames after the restart";
}

void RunMetrics::Carry(std::size_t samples, double swarm_count_sum, std::size_t done,
                       std::size_t aborted) {
  samples_ += samples;
  swarm_count_sum_ += swarm_count_sum;
  missions_done_ += done;
  missions_aborted_ += aborted;
}

std::string RunMetrics::AddResent(const MissionSpec* order, std::uint16_t mission_id,
                                  MissionPhase phase, std::uint64_t tick, Vec2 object) {
  if (phase == MissionPhase::kRejected || rows_of_.count(mission_id) > 0) return "";
  auto it = missions_.find(mission_id);
  if (it == missions_.end()) {
    if (missions_.size() >= kMaxMissions) {
      return "not following mission " + std::to_string(mission_id) + ": " +
             std::to_string(missions_.size()) + " missions followed already";
    }
    it = missions_.emplace(mission_id, MissionRecord()).first;
    it->second.recovered = true;
  }
  MissionRecord& m = it->second;
  if (m.final_state) return "";
  const bool any_phase = std::any_of(m.entered.begin(), m.entered.end(),
                                     [](const auto& tick) { return tick.has_value(); });
  // Nothing booked of it but perhaps an order heard on the topic (a latched one may be a raw
  // order the dispatcher refused): it is recovered, and the order its first leader carries is
  // the one it runs.
  if (!any_phase) m.recovered = true;
  if (order != nullptr && order->id == mission_id && (!m.has_spec || !any_phase)) {
    m.spec = *order;
    m.has_spec = true;
  }
  // A status of a phase already booked adds nothing; a new one is booked as a status is.
  if (m.entered[static_cast<std::size_t>(phase)]) return "";
  return AddStatus(mission_id, phase, tick, object);
}

}  // namespace core
}  // namespace swarm_transport
