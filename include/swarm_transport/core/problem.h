// The one sentence a parameter check returns: "<field> must be <requirement> but is <value>".
#ifndef SWARM_TRANSPORT_CORE_PROBLEM_H_
#define SWARM_TRANSPORT_CORE_PROBLEM_H_

#include <sstream>
#include <string>

namespace swarm_transport {
namespace core {

inline std::string Problem(const std::string& field, const std::string& requirement, double value) {
  std::ostringstream out;
  out << field << " must be " << requirement << " but is " << value;
  return out.str();
}

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_PROBLEM_H_
