#include <algorithm>
#include <thread>

#include "airr/core/error.hpp"
#include "airr/render/render_session.hpp"

namespace airr {

render_snapshot render_to_spp(render_session& session, std::uint64_t spp,
                              const std::function<bool(std::uint64_t)>& keep_going, std::chrono::milliseconds poll,
                              const std::function<std::uint64_t(std::uint64_t)>& job_spp) {
  render_snapshot snap;
  while (true) {
    snap = session.snapshot();
    if (!snap.error.empty()) {
      session.stop();
      throw input_error(snap.error);
    }
    const std::uint64_t done = job_spp ? job_spp(snap.spp) : snap.spp;
    if (done >= spp) break;
    if (keep_going && !keep_going(done)) break;
    const std::uint64_t next = std::min<std::uint64_t>(spp, snap.spp + 1);
    if (snap.spp >= spp)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the other ranks' turn
    else if (poll.count() > 0)
      session.wait_for(0, next, poll);
    else
      session.wait_for(0, next);
  }
  session.stop();
  return snap;
}

}  // namespace airr
