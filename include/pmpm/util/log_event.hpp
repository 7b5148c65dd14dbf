// A PETSc profiling event over a scope: begun where it is declared, ended where the scope ends,
// on every path out of it (an error's early return included, so -log_view's event nesting stays
// balanced), instead of a PetscLogEventBegin/End pair that every exit must match:
//   if (iface) {
//     PmpmLogEventScope(ev_iface);
//     ...
//   }
// The begin is checked (PetscCall); the end, in a destructor, cannot return an error:
// PetscLogEventEnd fails only on a corrupt log, which the next checked begin reports.
#pragma once
#include <petsclog.h>

namespace pmpm {

class LogEventScope {
public:
  LogEventScope() = default;
  LogEventScope(const LogEventScope &) = delete;
  LogEventScope &operator=(const LogEventScope &) = delete;
  ~LogEventScope() {
    if (on_) (void)PetscLogEventEnd(e_, 0, 0, 0, 0);
  }
  PetscErrorCode begin(PetscLogEvent e) {
    PetscFunctionBeginUser;
    PetscCall(PetscLogEventBegin(e, 0, 0, 0, 0));
    e_ = e;
    on_ = true;
    PetscFunctionReturn(0);
  }

private:
  PetscLogEvent e_ = 0;
  bool on_ = false;
};

} // namespace pmpm

#define PMPM_LOG_SCOPE_CAT2(a, b) a##b
#define PMPM_LOG_SCOPE_CAT(a, b) PMPM_LOG_SCOPE_CAT2(a, b)
// Inside a function returning PetscErrorCode: the event ev from here to the end of the scope.
#define PmpmLogEventScope(ev)                                                                      \
  pmpm::LogEventScope PMPM_LOG_SCOPE_CAT(pmpm_log_scope_, __LINE__);                               \
  PetscCall(PMPM_LOG_SCOPE_CAT(pmpm_log_scope_, __LINE__).begin(ev))
