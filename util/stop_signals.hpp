// The stop requests of a long run: while a StopSignalHandlers lives, SIGINT (Ctrl-C), SIGTERM and
// SIGHUP (unless SIGHUP is ignored, as under nohup) go to the caller's handler, and optionally
// SIGPIPE is ignored; the previous dispositions come back when it ends. One place for the runs that
// stop at a safe point on a request (`hydrojump sph`, `hydrojump vof`, `hydrojump study`).
//
//   | option                     | meaning                                                        |
//   |----------------------------|----------------------------------------------------------------|
//   | restart_interrupted_calls  | SA_RESTART: a write the signal interrupts is restarted          |
//   | ignore_sigpipe             | a write to a pipe a hangup closed fails instead of killing     |
// Example:
//   const StopSignalHandlers handlers(on_stop_request, {.restart_interrupted_calls = true});
#pragma once

#include <csignal>

namespace hydrojump::util {

// The name of a stop request's signal, for messages ("stopped by SIGTERM").
inline const char* stop_signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

struct StopSignalOptions {
  bool restart_interrupted_calls = false;
  bool ignore_sigpipe = false;
};

class StopSignalHandlers {
 public:
  StopSignalHandlers(void (*handler)(int), StopSignalOptions options) : ignore_sigpipe_(options.ignore_sigpipe) {
    struct sigaction sa {};
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = options.restart_interrupted_calls ? SA_RESTART : 0;
    ::sigaction(SIGINT, &sa, &old_int_);
    ::sigaction(SIGTERM, &sa, &old_term_);
    ::sigaction(SIGHUP, nullptr, &old_hup_);
    if (old_hup_.sa_handler != SIG_IGN) ::sigaction(SIGHUP, &sa, nullptr);
    if (ignore_sigpipe_) {
      struct sigaction ignore {};
      ignore.sa_handler = SIG_IGN;
      sigemptyset(&ignore.sa_mask);
      ::sigaction(SIGPIPE, &ignore, &old_pipe_);
    }
  }
  ~StopSignalHandlers() {
    ::sigaction(SIGINT, &old_int_, nullptr);
    ::sigaction(SIGTERM, &old_term_, nullptr);
    ::sigaction(SIGHUP, &old_hup_, nullptr);
    if (ignore_sigpipe_) ::sigaction(SIGPIPE, &old_pipe_, nullptr);
  }
  StopSignalHandlers(const StopSignalHandlers&) = delete;
  StopSignalHandlers& operator=(const StopSignalHandlers&) = delete;

 private:
  bool ignore_sigpipe_;
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
  struct sigaction old_hup_ {};
  struct sigaction old_pipe_ {};
};

}  // namespace hydrojump::util
