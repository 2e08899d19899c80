#include "driver/interrupted_record.h"

namespace wl {

bool signal_received() { return interrupt_signal() != 0; }

void mark_interrupted(Json& record, const std::string& stage) {
  record.set("outcome", "interrupted");
  record.set("interrupted_in", stage);
  record.set("message", interrupted_message(interrupt_signal()));
}

}  // namespace wl
