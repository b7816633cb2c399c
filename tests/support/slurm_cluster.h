#pragma once
// A real single-node Slurm cluster for the farm tests, from Debian's packages (munge,
// slurmctld, slurmd: scripts/setup --test installs them): a munge key, a slurm.conf and the
// daemons' state in a temporary directory, the node sized from this machine (nproc, memory),
// every daemon in the foreground as a child of the test, stopped (and waited for) at the
// end. SLURM_CONF is set in the test process, so `glint farm` and the tasks it submits (they
// inherit the environment) use this cluster and no other.
//
//   SlurmCluster cluster;                  // throws std::runtime_error with the daemons' logs
//   runGlint("farm cut ... --wait");
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace glint::testing {

class SlurmCluster {
public:
  /// Starts munged, slurmctld and slurmd and waits (up to 30 s) until the node is idle.
  explicit SlurmCluster(const std::filesystem::path& directory) : m_dir(directory) {
    namespace fs = std::filesystem;
    fs::remove_all(m_dir);
    fs::create_directories(m_dir / "munge");
    fs::create_directories(m_dir / "state");
    fs::create_directories(m_dir / "spool");
    fs::create_directories(m_dir / "log");
    fs::permissions(m_dir / "munge", fs::perms::owner_all);
    {
      std::ifstream random("/dev/urandom", std::ios::binary);
      std::string key(1024, '\0');
      random.read(key.data(), std::streamsize(key.size()));
      std::ofstream(m_dir / "munge" / "munge.key", std::ios::binary) << key;
      fs::permissions(m_dir / "munge" / "munge.key", fs::perms::owner_read);
    }
    const std::string socket = (m_dir / "munge" / "socket").string();
    try {  // a cluster that does not start leaves no daemon behind (the catch below)
      start({"munged", "--foreground", "--force", "--socket=" + socket,
             "--key-file=" + (m_dir / "munge" / "munge.key").string(), "--log-file=" + (m_dir / "log" / "munged.log").string(),
             "--pid-file=" + (m_dir / "munge" / "munged.pid").string(), "--seed-file=" + (m_dir / "munge" / "seed").string()},
            "munged.out");
      waitFor([&] { return fs::exists(socket); }, "munged's socket");

      char host[256] = {};
      gethostname(host, sizeof host - 1);
      m_node = std::string(host).substr(0, std::string(host).find('.'));
      const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
      const long long memoryMiB = (long long)(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGE_SIZE) / (1024 * 1024);
      const std::string conf = (m_dir / "slurm.conf").string();
      std::ofstream(conf) << "# A one-node cluster for glint's farm tests (tests/support/slurm_cluster.h)\n"
                          << "ClusterName=glinttest\n"
                          << "SlurmctldHost=" << m_node << "(127.0.0.1)\n"
                          << "SlurmUser=root\nSlurmdUser=root\n"
                          << "SlurmctldPort=" << freePort() << "\nSlurmdPort=" << freePort() << "\n"
                          << "AuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket=" << socket << "\n"
                          << "StateSaveLocation=" << (m_dir / "state").string() << "\n"
                          << "SlurmdSpoolDir=" << (m_dir / "spool").string() << "\n"
                          << "SlurmctldPidFile=" << (m_dir / "slurmctld.pid").string() << "\n"
                          << "SlurmdPidFile=" << (m_dir / "slurmd.pid").string() << "\n"
                          << "SlurmctldLogFile=" << (m_dir / "log" / "slurmctld.log").string() << "\n"
                          << "SlurmdLogFile=" << (m_dir / "log" / "slurmd.log").string() << "\n"
                          << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\nSwitchType=switch/none\n"
                          << "MpiDefault=none\nReturnToService=2\nSchedulerType=sched/backfill\n"
                          << "SchedulerParameters=sched_interval=1\n"
                          << "SelectType=select/cons_tres\nSelectTypeParameters=CR_Core_Memory\n"
                          << "JobCompType=jobcomp/none\nAccountingStorageType=accounting_storage/none\n"
                          << "JobAcctGatherType=jobacct_gather/none\nMinJobAge=300\n"
                          << "NodeName=" << m_node << " NodeAddr=127.0.0.1 CPUs=" << cpus
                          << " RealMemory=" << std::max(1024LL, memoryMiB - 512) << " State=UNKNOWN\n"
                          << "PartitionName=glint Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n";
      // Slurm 23.11 and later (Debian 13: 24.11) start slurmd's cgroup plugin even with the
      // plugins above, and fail where no cgroup filesystem is mounted (a container, a chroot):
      // a test cluster needs none. Debian 12's 22.05 reads no cgroup.conf for these plugins
      // and does not know the value.
      if (slurmVersion() >= 2311) std::ofstream(m_dir / "cgroup.conf") << "CgroupPlugin=disabled\n";
      setenv("SLURM_CONF", conf.c_str(), 1);
      start({"slurmctld", "-D", "-i", "-f", conf}, "slurmctld.out");
      start({"slurmd", "-D", "-N", m_node, "-f", conf}, "slurmd.out");
      waitFor([&] { return shell("sinfo -h -o %t").find("idle") != std::string::npos; }, "the node to be idle");
    } catch (...) {
      stop();
      throw;
    }
  }

  ~SlurmCluster() { stop(); }

  /// Slurm's version as yymm (24.11.5 → 2411); 0 when slurmd does not say.
  static int slurmVersion() {
    const std::string text = shell(daemonPath("slurmd") + " -V");  // "slurm-wlm 24.11.5" (Debian), "slurm 24.11.5"
    const auto space = text.find(' ');
    int major = 0, minor = 0;
    if (space == std::string::npos || std::sscanf(text.c_str() + space, " %d.%d", &major, &minor) != 2) return 0;
    return major * 100 + minor;
  }

  /// Ends the jobs, then the daemons (slurmd, slurmctld, munged: the reverse of their start).
  void stop() {
    // Jobs still running (a test that failed half-way) end first, so no job step outlives
    // the daemons.
    shell("scancel --user=$(id -un)");
    for (int i = 0; i < 100 && !shell("squeue -h").empty(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (auto it = m_pids.rbegin(); it != m_pids.rend(); ++it) kill(*it, SIGTERM);
    for (pid_t pid : m_pids) {
      int status = 0;
      for (int i = 0; i < 100 && waitpid(pid, &status, WNOHANG) == 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (waitpid(pid, &status, WNOHANG) == 0) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
      }
    }
    m_pids.clear();
    unsetenv("SLURM_CONF");
  }

  SlurmCluster(const SlurmCluster&) = delete;
  SlurmCluster& operator=(const SlurmCluster&) = delete;

  const std::filesystem::path& directory() const { return m_dir; }

  /// A shell command's stdout (e.g. squeue) with this cluster's SLURM_CONF.
  static std::string shell(const std::string& command) {
    std::string out;
    FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
    char buffer[4096];
    while (pipe && fgets(buffer, sizeof buffer, pipe)) out += buffer;
    if (pipe) pclose(pipe);
    return out;
  }

  /// The daemons' logs, for a failure message.
  std::string logs() const {
    std::string text;
    for (const char* name : {"munged.out", "slurmctld.out", "slurmd.out"}) {
      std::ifstream in(m_dir / "log" / name);
      std::stringstream s;
      s << in.rdbuf();
      text += std::string("== ") + name + "\n" + s.str();
    }
    return text;
  }

private:
  static int freePort() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = 0;
    bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
    socklen_t length = sizeof address;
    getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
    const int port = ntohs(address.sin_port);
    close(fd);
    return port;
  }

  /// The daemons live in sbin, which a user's PATH need not name (Debian's default PATH for a
  /// user has no /usr/sbin): PATH first, then /usr/sbin and /sbin. Empty if none has it.
  static std::string daemonPath(const std::string& name) {
    std::string search = std::getenv("PATH") ? std::getenv("PATH") : "";
    search += ":/usr/sbin:/sbin";
    std::stringstream folders(search);
    for (std::string folder; std::getline(folders, folder, ':');) {
      if (folder.empty()) continue;
      const std::string candidate = folder + "/" + name;
      if (access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return {};
  }

  void start(const std::vector<std::string>& argv, const std::string& log) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string path = (m_dir / "log" / log).string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const std::string program = daemonPath(argv[0]);
    pid_t pid = 0;
    const int e = program.empty() ? ENOENT : posix_spawn(&pid, program.c_str(), &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (e != 0) throw std::runtime_error("cannot start " + argv[0] + " (scripts/setup --test installs slurm-wlm and munge)");
    m_pids.push_back(pid);
  }

  template <class Ready>
  void waitFor(Ready ready, const std::string& what) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!ready()) {
      for (pid_t pid : m_pids) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) throw std::runtime_error("a Slurm daemon exited while waiting for " + what + "\n" + logs());
      }
      if (std::chrono::steady_clock::now() > until) throw std::runtime_error("timed out waiting for " + what + "\n" + logs());
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  std::filesystem::path m_dir;
  std::string m_node;
  std::vector<pid_t> m_pids;
};

}  // namespace glint::testing
