// `fe2heart study STUDY.json --out DIR`: runs each variant of a base scene as a child
// `fe2heart run` (under mpirun for NP > 1), measures what it cost, compares it with a
// reference on the declared quantities, and writes study.json, study.csv, study.txt and
// pareto.png. A failed variant stays in the results; only bad input stops the study.
#include "common/hash.h"
#include "common/io/atomic_file.h"
#include "coordinator/RunSpec.h"
#include "tools/commands.h"
#include "tools/output_folder.h"
#include "tools/study_error.h"
#include "tools/study_spec.h"

#include <mpi.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ranges>
#include <regex>
#include <thread>

extern char** environ;

namespace fe2::cli {

namespace {

namespace fs = std::filesystem;

/// What one variant cost and how it ended.
struct VariantResult {
  /// "ok" (ran to its end and converged), "failed", or "stopped" (by a signal, at a
  /// checkpoint that --resume continues from)
  std::string status = "not run";
  int exit_code = 0;
  std::string reason;  ///< a failed or stopped variant's last error line or how it stopped
  double wall = 0, cpu = 0, core_hours = 0, peak_rss_mb = 0;
  json summary;  ///< its summary.json (null if none)
  std::map<std::string, QuantityError> errors;
  double error = -1;  ///< max over quantities; < 0: none
  bool pareto = false;
  bool kept = false;       ///< --resume: finished by an earlier study in the same folder
  bool continued = false;  ///< --resume: continued from the checkpoint an earlier study stopped it at
};

/// What `--resume` compares before keeping or continuing a variant of an earlier study,
/// and the cost so far: DIR/variants/NAME/result.json, written when the variant ends or stops.
json variant_record(const StudyVariant& v, const VariantResult& r, int np, const std::vector<std::string>& launcher,
                    const std::string& program) {
  json j = {{"spec", v.spec},         {"np", np},           {"launcher", launcher},
            {"program", program},     {"status", r.status}, {"exit_code", r.exit_code},
            {"wall_seconds", r.wall}, {"cpu_seconds", r.cpu}, {"peak_rss_mb", r.peak_rss_mb}};
  if (!r.reason.empty()) j["reason"] = r.reason;
  return j;
}

/// What an earlier study left of variant `v` in `dir`, for --resume.
enum class Earlier { none, keep, continue_run };

/// `keep`: it ended "ok" with this spec, ranks and launcher and its run is complete;
/// `continue_run`: it was stopped, or killed by a signal, and its run has a checkpoint,
/// with the same spec, ranks and launcher; r then holds the cost so
/// far (and for `keep`, the summary). `why` says otherwise why it runs from the start.
Earlier earlier_variant(const StudyVariant& v, const fs::path& dir, int np, const std::vector<std::string>& launcher,
                        const std::string& program, VariantResult& r, std::string& why) {
  json rec, summary;
  if (!fs::exists(dir / "result.json")) {
    why = "no earlier result (a new variant, or the earlier study stopped before it ended)";
    return Earlier::none;
  }
  try {
    rec = read_json_file((dir / "result.json").string());
  } catch (const InputError& e) {
    why = e.what();
    return Earlier::none;
  }
  const std::string status = rec.is_object() ? rec.value("status", "") : "";
  if (status == "ok") {  // only a kept variant needs its summary (a killed one may have none)
    try {
      summary = read_json_file((dir / "run" / "summary.json").string());
    } catch (const InputError& e) {
      why = fmt::format("its run's summary.json cannot be read ({})", e.what());
      return Earlier::none;
    }
  }
  const bool complete = summary.is_object() && summary.value("converged", false) && summary.value("complete", false);
  Earlier earlier = Earlier::none;
  // A variant killed by a signal (exit code 128 + signal) after a checkpoint goes on from
  // it as a stopped one does: the checkpoint is whole (written atomically).
  const bool killed = status == "failed" && rec.value("exit_code", 0) >= 128;
  const bool resumable = status == "stopped" || killed;
  if (status != "ok" && !resumable)
    why = fmt::format("it ended \"{}\"", status);
  else if (rec.value("spec", json()) != v.spec)
    why = "its spec changed";
  else if (rec.value("np", -1) != np || rec.value("launcher", json()) != json(launcher))
    why = "its ranks or launcher changed";
  else if (status == "ok" && !complete)
    why = "its run's summary.json does not say complete and converged";
  else if (resumable && !fs::exists(dir / "run" / "checkpoint.bin"))
    why = fmt::format("it was {}, and its run has no checkpoint.bin", killed ? "killed" : "stopped");
  else
    earlier = status == "ok" ? Earlier::keep : Earlier::continue_run;
  if (earlier == Earlier::none) return earlier;
  try {
    r.exit_code = rec.at("exit_code").get<int>();
    r.wall = rec.at("wall_seconds").get<double>();
    r.cpu = rec.at("cpu_seconds").get<double>();
    r.peak_rss_mb = rec.at("peak_rss_mb").get<double>();
  } catch (const json::exception& e) {
    why = fmt::format("its result.json is incomplete ({})", e.what());
    r = VariantResult{};
    return Earlier::none;
  }
  const std::string earlier_program = rec.value("program", "");
  if (earlier_program != program)
    spdlog::warn("variant '{}' is {} a run by another build of fe2heart (fingerprint {}, this one {}); "
                 "use --overwrite to run every variant again",
                 v.name, earlier == Earlier::keep ? "kept from" : "continued from the checkpoint of", earlier_program,
                 program);
  if (earlier == Earlier::keep) {
    r.status = "ok";
    r.core_hours = r.wall * np / 3600.0;
    r.summary = std::move(summary);
    r.kept = true;
  } else {
    r.continued = true;
  }
  return earlier;
}

/// A fingerprint of this fe2heart binary: --resume warns when kept results came from another build.
std::string program_fingerprint(const std::string& self) {
  std::ifstream in(self, std::ios::binary);
  Fnv1a h;
  std::vector<char> buffer(1 << 16);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0)
    h.add(buffer.data(), static_cast<size_t>(in.gcount()));
  return fmt::format("{:016x}", h.value());
}

/// Variables the launcher of *this* process set (when it was itself started by mpirun)
/// would make a nested mpirun or singleton think it is part of our job; the user's own
/// OMPI_MCA_* settings (oversubscribe, run as root, ...) pass through.
bool launcher_variable(const std::string& v) {
  static const char* prefixes[] = {"PMIX_", "OMPI_COMM_WORLD", "OMPI_UNIVERSE_SIZE", "OMPI_FIRST_RANKS",
                                   "OMPI_APP_CTX", "OMPI_NUM_APP_CTX", "OMPI_FILE_LOCATION", "OMPI_ARGV",
                                   "OMPI_COMMAND", "OMPI_MCA_orte_", "OMPI_MCA_ess", "OMPI_MCA_pmix",
                                   "OMPI_MCA_initial_wdir", "OMPI_MCA_shmem_RUNTIME_QUERY",
                                   "OMPI_MCA_mpi_oversubscribe"};  // what Open MPI 4.1's mpirun sets
  for (const char* p : prefixes)
    if (v.rfind(p, 0) == 0) return true;
  return false;
}

/// The last error line of a variant's console log (spdlog "[error]"/"[critical]", or
/// failing that, its last non-empty line), without terminal colours.
std::string last_error_line(const std::string& log) {
  std::ifstream in(log);
  std::string line, error, last;
  static const std::regex colour("\x1b\\[[0-9;]*m");
  while (std::getline(in, line)) {
    line = std::regex_replace(line, colour, "");
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    last = line;
    if (line.find("[error]") != std::string::npos || line.find("[critical]") != std::string::npos) error = line;
  }
  // Without the log's "[time] [level] " prefix.
  static const std::regex prefix("^\\[[0-9:. -]+\\] \\[[a-z]+\\] ");
  return std::regex_replace(error.empty() ? last : error, prefix, "");
}

/// A stop request to the study: SIGTERM (a batch system's time limit, `timeout`), SIGINT
/// (Ctrl-C), SIGHUP (a lost terminal) or SIGQUIT. The handler only records it; run_child
/// passes it on to the running variant (which has its own process group, so nothing
/// reaches it but through the study):
///   first request:       the variant's stop file (`run --stop-file`) is written. `fe2heart
///                        run` writes a checkpoint at the next step boundary and stops;
///                        --resume continues it. Not SIGUSR1: mpirun forwards it at once,
///                        and a rank between its exec and main dies of it.
///   a second, >= 5 s later: SIGTERM (mpirun ends its ranks at once).
///   a third,  >= 5 s later: SIGKILL to the variant's process group.
/// Requests closer than 5 s to the first count as one: `timeout` signals the study and
/// then its process group.
volatile sig_atomic_t g_stop_signal = 0;
volatile sig_atomic_t g_stop_count = 0;
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

extern "C" void record_stop_signal(int sig) {
  g_stop_signal = sig;
  g_stop_count = g_stop_count + 1;
}

/// Installs record_stop_signal for kStopSignals while alive; restores the old handlers.
class StopSignalForwarding {
 public:
  StopSignalForwarding() {
    struct sigaction a {};
    a.sa_handler = record_stop_signal;
    sigemptyset(&a.sa_mask);
    for (size_t i = 0; i < std::size(kStopSignals); ++i) sigaction(kStopSignals[i], &a, &old_[i]);
  }
  ~StopSignalForwarding() {
    for (size_t i = 0; i < std::size(kStopSignals); ++i) sigaction(kStopSignals[i], &old_[i], nullptr);
  }
  StopSignalForwarding(const StopSignalForwarding&) = delete;
  StopSignalForwarding& operator=(const StopSignalForwarding&) = delete;

 private:
  struct sigaction old_[std::size(kStopSignals)] {};
};

/// Passes the study's stop requests on to one running variant, escalating as above.
class StopRelay {
 public:
  StopRelay(pid_t child, std::string stop_file) : child_(child), stop_file_(std::move(stop_file)) {}
  /// Called while the child is alive and not yet reaped (so its pid is its own).
  void poll() {
    using namespace std::chrono;
    const auto now = steady_clock::now();
    const int count = g_stop_count;
    if (count > seen_) {
      if (seen_ == 0) {
        first_ = now;
        level_ = 1;
      } else if (now - first_ >= seconds(5) && level_ < 3) {
        ++level_;
        first_ = now;  // the next step needs another 5 s
      }
      seen_ = count;
      send(now);
    } else if (level_ == 2 && now - sent_ >= seconds(2)) {
      send(now);  // mpirun may not have been able to act on it yet
    }
  }

 private:
  void send(std::chrono::steady_clock::time_point now) {
    if (level_ == 1) std::ofstream(stop_file_) << "stop requested by fe2heart study\n";
    if (level_ == 2) kill(child_, SIGTERM);
    if (level_ == 3) kill(-child_, SIGKILL);
    sent_ = now;
  }
  pid_t child_;
  std::string stop_file_;
  int seen_ = 0, level_ = 0;
  std::chrono::steady_clock::time_point first_{}, sent_{};
};

/// run_child's answer when a stop request came before the variant could start.
constexpr int kNotStarted = -1;

/// Runs argv with stdout and stderr to `log`; wall seconds and the child's rusage
/// (wait4: its CPU time and that of the processes it waited for, e.g. mpirun's ranks).
/// A stop request is passed on through `stop_file` (the variant's `run --stop-file`).
int run_child(const std::vector<std::string>& argv, const std::string& log, bool append, const std::string& stop_file,
              VariantResult& r) {
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e)
    if (!launcher_variable(*e)) env_strings.emplace_back(*e);
  std::vector<char*> envp, args;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::vector<std::string> argv_copy = argv;
  for (auto& a : argv_copy) args.push_back(a.data());
  args.push_back(nullptr);

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | (append ? O_APPEND : O_TRUNC),
                                   0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  // No stop request may fall between the last look at g_stop_count and the spawn.
  sigset_t stop, previous;
  sigemptyset(&stop);
  for (int sig : kStopSignals) sigaddset(&stop, sig);
  sigprocmask(SIG_BLOCK, &stop, &previous);
  if (g_stop_count > 0) {
    sigprocmask(SIG_SETMASK, &previous, nullptr);
    posix_spawn_file_actions_destroy(&fa);
    return kNotStarted;
  }
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setsigmask(&attr, &previous);
  posix_spawnattr_setsigdefault(&attr, &stop);
  // Its own process group: Ctrl-C at a terminal or a lost terminal's SIGHUP reaches only
  // the study, which passes the stop on, instead of killing the variant outright.
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
  const int rc = posix_spawnp(&pid, args[0], &fa, &attr, args.data(), envp.data());
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&fa);
  sigprocmask(SIG_SETMASK, &previous, nullptr);
  if (rc != 0) {
    r.reason = fmt::format("cannot start '{}': {}", argv[0], std::strerror(rc));
    return 127;
  }
  int status = 0;
  struct rusage ru {};
  // Polled rather than blocking, so that stop requests are passed on as they come.
  StopRelay relay(pid, stop_file);
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &ru);
    if (done == pid) break;
    if (done < 0 && errno != EINTR)
      throw Error(fmt::format("wait4 for '{}' failed: {}", argv[0], std::strerror(errno)));
    relay.poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.cpu = ru.ru_utime.tv_sec + 1e-6 * ru.ru_utime.tv_usec + ru.ru_stime.tv_sec + 1e-6 * ru.ru_stime.tv_usec;
  r.peak_rss_mb = ru.ru_maxrss / 1024.0;  // kB on Linux
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) {
    r.reason = fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
    return 128 + WTERMSIG(status);
  }
  return 1;
}

std::string number(double x, const char* fmt_spec = "{:.3g}") {
  return x < 0 || !std::isfinite(x) ? std::string("-") : fmt::format(fmt::runtime(fmt_spec), x);
}

long long summary_int(const json& s, const json::json_pointer& p) {
  return s.is_object() && s.contains(p) && s.at(p).is_number() ? s.at(p).get<long long>() : -1;
}

double summary_double(const json& s, const json::json_pointer& p) {
  return s.is_object() && s.contains(p) && s.at(p).is_number() ? s.at(p).get<double>() : -1.0;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) {
    if (c == '"') quoted += '"';  // doubled, as RFC 4180 has it
    quoted += c;
  }
  return quoted + '"';
}

/// Every variant must be a valid run spec before any runs (an error names the variant).
void check_variants(const StudySpec& s, const std::string& out) {
  for (const StudyVariant& v : s.variants) {
    const std::string file = (fs::path(out) / "variants" / v.name / "spec.json").string();
    try {
      (void)read_run_spec(v.spec, file, nullptr, /*build_units=*/false);
    } catch (const InputError& e) {
      throw InputError(fmt::format("study file '{}': variant '{}' (set {}) is not a valid run spec: {}", s.file,
                                   v.name, v.set.dump(), e.what()));
    }
  }
}

}  // namespace

int validate_study(const std::string& file) {
  const StudySpec s = read_study_spec(file);
  check_variants(s, "DIR");
  fmt::print("{}: OK: study of {} with {} variants ({}); reference {}; quantities {}\n", file, s.base,
             s.variants.size(), fmt::join(s.variants | std::views::transform(&StudyVariant::name), ", "),
             s.reference == StudySpec::Reference::run       ? "run " + s.reference_run
             : s.reference == StudySpec::Reference::variant ? s.reference_variant
                                                            : std::string("finest"),
             fmt::join(s.quantities, ", "));
  return 0;
}

int study(const StudyOptions& o) {
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (ranks != 1)
    throw InputError(fmt::format("fe2heart study runs as one process ({} ranks here); it starts each variant "
                                 "under mpirun itself (\"np\" in the study file, or --np)",
                                 ranks));
  StudySpec s = read_study_spec(o.spec);
  const int np = o.np > 0 ? o.np : s.np;
  std::vector<std::string> launcher;
  for (std::string a : s.mpirun) {
    for (size_t at; (at = a.find("{np}")) != std::string::npos;) a.replace(at, 4, std::to_string(np));
    launcher.push_back(a);
  }
  if (s.mpirun.empty() && np > 1) launcher = {"mpirun", "-n", std::to_string(np)};

  // The output folder: an earlier study is refused without --overwrite, before anything is written.
  std::error_code ec;
  std::vector<std::string> earlier;
  for (const char* name : {"study.json", "variants"})
    if (fs::exists(fs::path(o.out) / name, ec)) earlier.emplace_back(name);
  refuse_earlier_output(o.out, "a study", earlier, o.overwrite, o.resume ? Resume::yes : Resume::no);

  check_variants(s, o.out);
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string program = program_fingerprint(self);
  std::vector<VariantResult> results(s.variants.size());
  std::vector<std::string> not_kept(s.variants.size());
  for (size_t i = 0; i < s.variants.size(); ++i) {
    const StudyVariant& v = s.variants[i];
    const fs::path d = fs::path(o.out) / "variants" / v.name;
    if (o.resume && earlier_variant(v, d, np, launcher, program, results[i], not_kept[i]) != Earlier::none)
      continue;
    fs::create_directories(d, ec);
    if (ec) throw InputError(fmt::format("--out '{}': cannot create '{}' ({})", o.out, d.string(), ec.message()));
    fs::remove(d / "result.json", ec);  // written again when this variant ends
    write_file_atomically((d / "spec.json").string(), v.spec.dump(2) + "\n");
  }

  fmt::print("study {}: {} variants of {}, {} rank{} each\n", s.file, s.variants.size(), s.base, np,
             np == 1 ? "" : "s");
  std::fflush(stdout);
  for (const StopSignalForwarding forwarding; size_t i : std::views::iota(size_t{0}, s.variants.size())) {
    const StudyVariant& v = s.variants[i];
    VariantResult& r = results[i];
    if (g_stop_signal != 0) break;
    if (r.kept) {
      fmt::print("[{}/{}] {}: ok, kept from the earlier study (CPU {:.1f} s)\n", i + 1, s.variants.size(), v.name,
                 r.cpu);
      std::fflush(stdout);
      continue;
    }
    const fs::path d = fs::path(o.out) / "variants" / v.name;
    const fs::path run_dir = d / "run";
    std::vector<std::string> argv = launcher;
    for (const std::string& a : {self, std::string("run"), (d / "spec.json").string(), std::string("--out"),
                                 run_dir.string()})
      argv.push_back(a);
    // A variant an earlier study stopped goes on from its checkpoint, in its own folder;
    // its cost is that of both parts.
    const VariantResult before = r;
    if (r.continued) {
      spdlog::info("variant '{}' continues from {}", v.name, (run_dir / "checkpoint.bin").string());
      argv.insert(argv.end(), {"--restart", run_dir.string()});
    } else {
      if (o.resume) spdlog::info("variant '{}' runs: {}", v.name, not_kept[i]);
      argv.push_back("--overwrite");
    }
    // Outside the run folder, which --overwrite clears; no earlier request may linger.
    const fs::path stop_file = d / "stop";
    fs::remove(stop_file, ec);
    argv.insert(argv.end(), {"--stop-file", stop_file.string()});
    const int exit_code = run_child(argv, (d / "run.log").string(), /*append=*/r.continued, stop_file.string(), r);
    fs::remove(stop_file, ec);
    if (exit_code == kNotStarted) {  // a stop came first: the variant stays as it was
      r = before;
      break;
    }
    r.exit_code = exit_code;
    r.wall += before.wall;
    r.cpu += before.cpu;
    r.peak_rss_mb = std::max(r.peak_rss_mb, before.peak_rss_mb);
    r.core_hours = r.wall * np / 3600.0;
    try {
      r.summary = read_json_file((run_dir / "summary.json").string());
    } catch (const InputError&) {
      r.summary = nullptr;
    }
    const bool summary = r.summary.is_object();
    if (r.exit_code == 0 && summary && r.summary.contains("stopped")) {
      r.status = "stopped";
      r.reason = fmt::format("stopped by a signal after step {}, at a checkpoint; --resume continues it",
                             r.summary.value("steps", -1));
    } else if (r.exit_code == 0 && summary && r.summary.value("converged", false) &&
               r.summary.value("complete", false)) {
      r.status = "ok";
    } else {
      r.status = "failed";
      if (r.reason.empty()) r.reason = last_error_line((d / "run.log").string());
      if (r.reason.empty()) r.reason = fmt::format("exit code {}", r.exit_code);
    }
    write_file_atomically((d / "result.json").string(),
                          variant_record(v, r, np, launcher, program).dump(2) + "\n");
    fmt::print("[{}/{}] {}: {}{} in {:.1f} s (CPU {:.1f} s){}\n", i + 1, s.variants.size(), v.name, r.status,
               r.continued ? ", continued from its checkpoint," : "", r.wall, r.cpu,
               r.status == "ok" ? "" : ": " + r.reason);
    std::fflush(stdout);
  }

  if (g_stop_signal != 0) {
    const int sig = g_stop_signal;
    spdlog::error("study {} stopped by signal {} ({}); what each variant did is recorded in "
                  "{}/variants/NAME/result.json; go on with: fe2heart study {} --out {} --resume",
                  s.file, sig, strsignal(sig), o.out, o.spec, o.out);
    return 128 + sig;
  }

  // The reference: a named variant, an earlier run, or the costliest variant that ran.
  std::string ref_dir, ref_name;
  std::string ref_problem;
  if (s.reference == StudySpec::Reference::run) {
    ref_dir = s.reference_run;
    ref_name = "run " + s.reference_run;
  } else {
    long best = -1;
    for (size_t i = 0; i < s.variants.size(); ++i) {
      if (s.reference == StudySpec::Reference::variant ? s.variants[i].name == s.reference_variant
                                                       : results[i].status == "ok" &&
                                                             (best < 0 || results[i].cpu > results[best].cpu))
        best = static_cast<long>(i);
    }
    if (best >= 0) {
      ref_name = s.variants[best].name;
      ref_dir = (fs::path(o.out) / "variants" / ref_name / "run").string();
      if (results[best].status != "ok") ref_problem = fmt::format("the reference variant '{}' failed", ref_name);
    } else {
      ref_problem = "no variant ran to the end, so there is no finest one";
    }
  }
  std::map<std::string, QuantitySeries> ref_q;
  if (ref_problem.empty())
    for (const std::string& q : s.quantities) try {
        ref_q[q] = read_quantity(ref_dir, q);
      } catch (const InputError& e) {
        ref_problem = fmt::format("reference {}: {}", ref_name, e.what());
      }
  if (!ref_problem.empty()) spdlog::warn("no errors computed: {}", ref_problem);

  for (size_t i = 0; i < s.variants.size() && ref_problem.empty(); ++i) {
    VariantResult& r = results[i];
    if (r.status != "ok") continue;
    const std::string dir = (fs::path(o.out) / "variants" / s.variants[i].name / "run").string();
    for (const std::string& q : s.quantities) {
      QuantityError e;
      try {
        e = compare_quantity(read_quantity(dir, q), ref_q[q]);
      } catch (const InputError& x) {
        e.note = x.what();
      }
      r.errors[q] = e;
      if (e.error >= 0) r.error = std::max(r.error, e.error);
    }
  }
  // The Pareto front over (CPU seconds, error): no other variant is as cheap and as accurate, and better in one.
  for (size_t i = 0; i < results.size(); ++i) {
    if (results[i].error < 0) continue;
    results[i].pareto = true;
    for (size_t k = 0; k < results.size(); ++k)
      if (k != i && results[k].error >= 0 && results[k].cpu <= results[i].cpu && results[k].error <= results[i].error &&
          (results[k].cpu < results[i].cpu || results[k].error < results[i].error))
        results[i].pareto = false;
  }

  // study.json
  json out = {{"study", s.file},
              {"title", s.title},
              {"base", s.base},
              {"np", np},
              {"launcher", launcher},
              {"quantities", s.quantities},
              {"reference", {{"name", ref_name}, {"dir", ref_dir}}},
              {"error_definition", "max over compared step times and entries of |q - q_ref|, divided by max |q_ref| "
                                   "(absolute if q_ref is 0); the reference interpolated linearly in time at each "
                                   "of the variant's step times"},
              {"cost_definition", "wall_seconds and cpu_seconds of the child process tree (wait4 rusage: user + "
                                  "system of mpirun and the ranks it waited for); core_hours = wall x np / 3600; "
                                  "peak_rss_mb: the largest process"}};
  if (!ref_problem.empty()) out["reference"]["problem"] = ref_problem;
  json vs = json::array();
  for (size_t i = 0; i < s.variants.size(); ++i) {
    const VariantResult& r = results[i];
    const json& sm = r.summary;
    json v = {{"name", s.variants[i].name},
              {"set", s.variants[i].set},
              {"status", r.status},
              {"exit_code", r.exit_code},
              {"wall_seconds", r.wall},
              {"cpu_seconds", r.cpu},
              {"core_hours", r.core_hours},
              {"peak_rss_mb", r.peak_rss_mb},
              {"newton_iterations", summary_int(sm, "/newton_iterations"_json_pointer)},
              {"gmres_iterations", summary_int(sm, "/gmres_iterations"_json_pointer)},
              {"refreshes", summary_int(sm, "/refreshes"_json_pointer)},
              {"macro_factorizations", summary_int(sm, "/macro_solver/factorizations"_json_pointer)},
              {"micro_cpu_seconds", summary_double(sm, "/micro_cpu_seconds"_json_pointer)},
              {"steps", summary_int(sm, "/steps"_json_pointer)},
              {"reference", s.variants[i].name == ref_name},
              {"kept_from_earlier_study", r.kept},
              {"continued_from_checkpoint", r.continued},
              {"pareto", r.pareto},
              {"run", (fs::path("variants") / s.variants[i].name / "run").string()}};
    if (!r.reason.empty()) v["reason"] = r.reason;
    v["error"] = r.error >= 0 ? json(r.error) : json(nullptr);
    json per = json::object();
    for (const auto& [q, e] : r.errors) {
      per[q] = {{"error", e.error >= 0 ? json(e.error) : json(nullptr)}, {"times", e.times}};
      if (!e.note.empty()) per[q]["note"] = e.note;
    }
    v["errors"] = per;
    vs.push_back(v);
  }
  out["variants"] = vs;
  write_file_atomically((fs::path(o.out) / "study.json").string(), out.dump(2) + "\n");

  // study.csv: one row per variant
  std::string csv = "name,status,exit_code,wall_seconds,cpu_seconds,core_hours,peak_rss_mb,newton_iterations,"
                    "gmres_iterations,refreshes,macro_factorizations,micro_cpu_seconds,error";
  for (const std::string& q : s.quantities) csv += ",error " + csv_field(q);
  csv += ",pareto,set,reason\n";
  for (const json& v : vs) {
    auto num = [](const json& x) { return x.is_null() ? std::string() : x.dump(); };
    csv += fmt::format("{},{},{},{:.3f},{:.3f},{:.6f},{:.1f},{},{},{},{},{:.3f},{}", csv_field(v["name"]),
                       v["status"].get<std::string>(), v["exit_code"].get<int>(), v["wall_seconds"].get<double>(),
                       v["cpu_seconds"].get<double>(), v["core_hours"].get<double>(), v["peak_rss_mb"].get<double>(),
                       v["newton_iterations"].dump(), v["gmres_iterations"].dump(), v["refreshes"].dump(),
                       v["macro_factorizations"].dump(), v["micro_cpu_seconds"].get<double>(), num(v["error"]));
    for (const std::string& q : s.quantities)
      csv += "," + (v["errors"].contains(q) ? num(v["errors"][q]["error"]) : std::string());
    csv += fmt::format(",{},{},{}\n", v["pareto"].get<bool>() ? 1 : 0, csv_field(v["set"].dump()),
                       csv_field(v.value("reason", "")));
  }
  write_file_atomically((fs::path(o.out) / "study.csv").string(), csv);

  // study.txt: the short table, also printed
  std::string txt = fmt::format("study {} ({} rank{} per variant); reference: {}\n", s.file, np,
                                np == 1 ? "" : "s", ref_problem.empty() ? ref_name : ref_problem);
  txt += fmt::format("error: max over {} of |q - q_ref| / max |q_ref|; * = Pareto front (CPU s, error)\n",
                     fmt::join(s.quantities, ", "));
  txt += fmt::format("{:<28} {:>7} {:>9} {:>9} {:>8} {:>7} {:>7} {:>9} {:>8} {:>10}\n", "variant", "status", "wall s",
                     "CPU s", "RSS MB", "Newton", "GMRES", "refreshes", "macro f.", "error");
  for (size_t i = 0; i < vs.size(); ++i) {
    const json& v = vs[i];
    const std::string name = v["name"].get<std::string>() + (v["pareto"].get<bool>() ? " *" : "");
    txt += fmt::format("{:<28} {:>7} {:>9.2f} {:>9.2f} {:>8.0f} {:>7} {:>7} {:>9} {:>8} {:>10}\n", name,
                       v["status"].get<std::string>(), v["wall_seconds"].get<double>(), v["cpu_seconds"].get<double>(),
                       v["peak_rss_mb"].get<double>(), number(v["newton_iterations"].get<double>(), "{:.0f}"),
                       number(v["gmres_iterations"].get<double>(), "{:.0f}"),
                       number(v["refreshes"].get<double>(), "{:.0f}"),
                       number(v["macro_factorizations"].get<double>(), "{:.0f}"),
                       v["reference"].get<bool>() ? std::string("reference")
                                                  : number(results[i].error, "{:.2e}"));
    if (results[i].status != "ok")
      txt += fmt::format("    {} (exit {}): {}\n", results[i].status, results[i].exit_code, results[i].reason);
  }
  write_file_atomically((fs::path(o.out) / "study.txt").string(), txt);
  fmt::print("{}", txt);

  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}' > /dev/null 2>&1", FE2_STUDY_PLOT_SCRIPT, o.out);
  if (std::system(cmd.c_str()) != 0)
    spdlog::warn("no pareto.png: '{}' failed (it needs Debian's python3-matplotlib)", cmd);
  fmt::print("results: {}/study.json, study.csv, study.txt, pareto.png\n", o.out);
  return 0;
}

}  // namespace fe2::cli
