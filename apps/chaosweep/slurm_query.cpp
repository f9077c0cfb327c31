#include "apps/chaosweep/slurm_query.hpp"

#include <set>
#include <sstream>

#include "apps/chaosweep/run_argv.hpp"
#include "apps/chaosweep/slurm_values.hpp"

namespace chaosweep {

namespace {

bool digits(const std::string& s, std::size_t max = 18) {
  return !s.empty() && s.size() <= max && s.find_first_not_of("0123456789") == std::string::npos;
}

// SLURM's state word: capitals and '_' ("CANCELLED by 1000" -> CANCELLED).
std::string state_word(const std::string& s) {
  const std::string w = s.substr(0, s.find(' '));
  return !w.empty() && w.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZ_") == std::string::npos ? w : "";
}

std::string exit_code_of(const std::string& s) {
  const std::size_t colon = s.find(':');
  return colon != std::string::npos && digits(s.substr(0, colon), 4) && digits(s.substr(colon + 1), 4) ? s : "";
}

// Calls `f(task)` for each task of "4", "[0-3,5%2]" or "0-3" below `tasks`.
template <class F>
void each_task(std::string spec, int tasks, F f) {
  if (!spec.empty() && spec.front() == '[') spec.erase(0, 1);
  if (!spec.empty() && spec.back() == ']') spec.pop_back();
  spec = spec.substr(0, spec.find('%'));  // the throttle
  std::stringstream in(spec);
  for (std::string part; std::getline(in, part, ',');) {
    const std::size_t dash = part.find('-');
    const std::string a = part.substr(0, dash), b = dash == std::string::npos ? a : part.substr(dash + 1);
    if (!digits(a, 9) || !digits(b, 9)) continue;
    for (long k = std::stol(a), last = std::min<long>(std::stol(b), tasks - 1); k <= last; ++k) f(int(k));
  }
}

void add(TaskStates& into, int tasks, const std::string& job, const std::string& task_spec, const std::string& state,
         const std::string& exit_code) {
  const std::string word = state_word(state);
  if (!digits(job) || word.empty()) return;
  const TaskState s{std::stoll(job), word, exit_code_of(exit_code)};
  each_task(task_spec, tasks, [&](int k) { merge_task_state(into, k, s); });
}

std::vector<std::string> fields(const std::string& line, char sep) {
  std::vector<std::string> f;
  std::stringstream in(line);
  for (std::string x; std::getline(in, x, sep);) f.push_back(x);
  return f;
}

std::string first_line(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  if (l.size() > 200) l.resize(200);
  return printable(l);
}

bool says_invalid_job(const ArgvResult& r) { return r.err.find("Invalid job id") != std::string::npos; }

std::string joined(const std::vector<std::string>& ids) {
  std::string s;
  for (const std::string& id : ids) s += (s.empty() ? "" : ",") + id;
  return s;
}

}  // namespace

bool slurm_state_pending(const std::string& state) {
  static const std::set<std::string> pending{"PENDING", "REQUEUED", "REQUEUE_HOLD", "REQUEUE_FED", "RESV_DEL_HOLD"};
  return pending.count(state) > 0;
}

bool slurm_state_live(const std::string& state) {
  static const std::set<std::string> running{"RUNNING",  "CONFIGURING", "COMPLETING", "SUSPENDED",
                                             "RESIZING", "SIGNALING",   "STAGE_OUT",  "STOPPED"};
  return slurm_state_pending(state) || running.count(state) > 0;
}

void merge_task_state(TaskStates& into, int task, const TaskState& s) {
  const auto it = into.find(task);
  if (it == into.end()) {
    into.emplace(task, s);
    return;
  }
  const bool live_old = slurm_state_live(it->second.state), live_new = slurm_state_live(s.state);
  if (live_new != live_old ? live_new : s.job >= it->second.job) it->second = s;
}

void parse_squeue(const std::string& out, int tasks, TaskStates& into) {
  std::stringstream in(out);
  for (std::string line; std::getline(in, line);) {
    const auto f = fields(line, '|');
    if (f.size() == 3) add(into, tasks, f[0], f[1], f[2], "");
  }
}

void parse_sacct(const std::string& out, int tasks, TaskStates& into) {
  std::stringstream in(out);
  for (std::string line; std::getline(in, line);) {
    const auto f = fields(line, '|');
    const std::size_t us = f.empty() ? std::string::npos : f[0].find('_');
    if (f.size() >= 3 && us != std::string::npos) add(into, tasks, f[0].substr(0, us), f[0].substr(us + 1), f[1], f[2]);
  }
}

void parse_scontrol(const std::string& out, int tasks, TaskStates& into) {
  std::stringstream in(out);
  for (std::string line; std::getline(in, line);) {
    std::map<std::string, std::string> kv;
    std::stringstream words(line);
    for (std::string w; words >> w;)
      if (const std::size_t eq = w.find('='); eq != std::string::npos) kv.emplace(w.substr(0, eq), w.substr(eq + 1));
    add(into, tasks, kv["ArrayJobId"], kv["ArrayTaskId"], kv["JobState"], kv["ExitCode"]);
  }
}

SlurmReport query_slurm(const std::vector<std::string>& array_jobs, int tasks) {
  SlurmReport rep;
  std::vector<std::string> ids;
  for (const std::string& id : array_jobs) {
    if (digits(id)) ids.push_back(id);
    else rep.notes.push_back("job id '" + printable(id) + "' is not a number: not asked");
  }
  if (ids.empty()) return rep;
  const ArgvResult q = run_argv({"squeue", "-h", "-r", "-j", joined(ids), "-o", "%F|%K|%T"});
  if (!q.started) {
    rep.notes.push_back("squeue is not on PATH: SLURM not asked, states from the shard locks only");
    return rep;
  }
  if (q.exit_code == 0 || says_invalid_job(q)) parse_squeue(q.out, tasks, rep.tasks);
  else
    rep.notes.push_back("squeue failed (" + first_line(q.timed_out ? "timed out" : q.err) +
                        "): live tasks known from the shard locks only");
  const ArgvResult a = run_argv({"sacct", "-n", "-P", "-X", "-j", joined(ids), "-o", "JobID,State,ExitCode"});
  if (a.started && a.exit_code == 0) {
    parse_sacct(a.out, tasks, rep.tasks);
    return rep;
  }
  // No accounting storage (or no sacct): the controller still knows the
  // jobs that ended less than MinJobAge ago.
  bool asked = false;
  for (const std::string& id : ids) {
    const ArgvResult c = run_argv({"scontrol", "-o", "show", "job", id});
    asked = asked || c.started;
    if (c.started && c.exit_code == 0) parse_scontrol(c.out, tasks, rep.tasks);
  }
  const std::string why = a.started ? "sacct failed (" + first_line(a.timed_out ? "timed out" : a.err) + ")"
                                    : std::string("sacct is not on PATH");
  rep.notes.push_back(why + (asked ? ": ended tasks from scontrol show job, which keeps them only for MinJobAge"
                                   : " and scontrol is not either: ended tasks unknown"));
  return rep;
}

}  // namespace chaosweep
