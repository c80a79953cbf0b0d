// What a restarted recorder takes over from the files an earlier recorder of the same run wrote
// (docs/reliability.md, "The recorder restarts"), pure: the texts in, what they hold out.
#ifndef SWARM_TRANSPORT_CORE_RECORD_RESUME_H_
#define SWARM_TRANSPORT_CORE_RECORD_RESUME_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>

namespace swarm_transport {
namespace core {

// Lines starting with this are comments (the gap, a recovered row): readers skip them.
constexpr char kCsvComment = '#';

struct EarlierRecord {
  std::set<std::uint16_t> rows;  // mission ids of missions.csv's rows
  std::size_t done = 0;          // ... of them DONE
  std::size_t aborted = 0;       // ... ABORTED
  std::size_t samples = 0;       // run.csv: samples and their mean swarm count
  double swarm_count_sum = 0.0;
  std::optional<std::uint64_t> last_tick;  // swarm_count.csv's last row, else run.csv's ticks
};

// The length of `text` up to and with its last newline: a last line without one was cut by the
// kill and is dropped (the file is cut back to this length before appending).
std::size_t CompleteLength(const std::string& text);

// Reads an earlier recorder's missions.csv, run.csv and swarm_count.csv (their texts, "" for a
// missing file; complete lines only). False with `error` when a header is not the one
// RunMetrics writes (not this package's files: the recorder refuses to append to them).
bool ReadEarlierRecord(const std::string& missions_csv, const std::string& run_csv,
                       const std::string& swarm_csv, EarlierRecord* out, std::string* error);

// The comment lines that mark a restart in missions.csv and swarm_count.csv: nothing was
// recorded after `last_tick` (none: nothing before), and from `tick` on it records again.
std::string GapComment(const std::optional<std::uint64_t>& last_tick, const std::string& when);
std::string ResumedComment(std::uint64_t tick);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RECORD_RESUME_H_
