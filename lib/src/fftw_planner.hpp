#pragma once
// FFTW's planner (plan creation and destruction) is not thread-safe; every module that plans
// takes this one process-wide lock. fftw_execute on distinct plans needs no lock.
#include <mutex>

namespace sigmatau::detail {

std::mutex& fftw_planner_mutex();

}  // namespace sigmatau::detail
