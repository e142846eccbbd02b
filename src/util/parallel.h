// Work split across threads by item index. Results must be stored per index by the caller, so
// output order and values never depend on the thread count.
#pragma once
#include <cstddef>
#include <functional>

namespace tsrir {

// Calls body(i) for i in [0, n) on up to num_threads threads (<= 1: the calling thread).
// The first exception thrown by any body is rethrown after all threads stop; remaining items
// are skipped once an exception is seen.
void parallel_for(size_t n, int num_threads, const std::function<void(size_t)>& body);

}  // namespace tsrir
