// mcar-sdformat: what libsdformat (Gazebo's URDF and SDF reader) makes of a robot.
//
//   mcar-sdformat [--sdf] < robot.urdf     (a URDF, or an SDF, on stdin)
//
// prints one JSON document on stdout (the fields: docs/gazebo.md):
//   interface, sdformat   this answer's format (2) and libsdformat's version (the
//                         SDF_VERSION_FULL it was built with: sdformat 12 has no call
//                         that tells the version at run time);
//   errors                libsdformat's verdict: the sdf::Errors its load returned, each
//                         {where: "error code N", text}; empty when it loaded the robot;
//   console_errors,       what urdfdom and libsdformat printed on their consoles at the
//   warnings              Error and Warning levels, each {where, text}: said in passing,
//                         not part of the verdict (libsdformat prints some errors that it
//                         then loads past, and returns none);
//   lumped, dropped       what libsdformat says it did to links, in its own words:
//                         lumped into their parent by a fixed joint ({link, into}), or
//                         left out, with every link below, for want of mass ({link, text});
//   model                 the model it loaded, or null: links (mass in kg, centre of mass
//                         in m, inertia about it in kg m^2, pose in the model frame in m
//                         and rad, collision, visual and sensor counts), joints (type,
//                         parent, child) and frames (attached to, and the link carrying it);
//   sdf                   with --sdf: the SDF libsdformat writes for it, as `gz sdf -p`
//                         prints it: what Gazebo spawns.
//
// It is given data only: the robot's text on stdin, never a path, and reads no other
// file (libsdformat converts a URDF without opening its meshes); it writes nothing but
// its answer (libsdformat's log file in ~/.sdformat is turned off by taking HOME away;
// what libraries print is kept in memory). libsdformat WOULD open files: an <include>
// in a <gazebo> block names a model folder or file (a path, file://, model://) that it
// reads into the SDF. mcar refuses such a robot before it gets here (E152), and the
// helper also confines itself (Confine below): once the dynamic loader has loaded the
// libraries and the console is set up, a seccomp filter lets through only the system
// calls that work on memory and on the files already open, so no file is opened or
// looked up (whether it exists included), no program runs, no socket opens.
// mcar runs it with a time, memory and output bound and checks the answer field by
// field (mobile_car/gazebo/wire.py, docs/security.md). Exit 0 when it answered (also
// about a robot libsdformat rejects: that is in `errors`), 2 on bad usage, input it
// could not read, or a kernel that would not confine it.
#include <sdf/sdf.hh>

#include <fcntl.h>
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

const int kInterface = 2;  // bumped when a field changes meaning (mcar checks it)
const size_t kMaxInput = size_t(1) << 30;  // mcar sends at most MCAR_MAX_INPUT_MB
// libsdformat quotes the whole robot in some errors ("Unable to read SDF string: ...").
const size_t kMaxMessage = 2000;
const size_t kMaxCaptured = size_t(16) << 20;  // urdfdom's own lines on stderr

std::string Clip(const std::string &text) {
  return text.size() <= kMaxMessage ? text : text.substr(0, kMaxMessage) + "...";
}

// A JSON string: control characters and anything not valid UTF-8 escaped, so the
// answer is always one valid document whatever names the robot holds.
std::string Quote(const std::string &text) {
  std::string out = "\"";
  size_t i = 0;
  while (i < text.size()) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
      ++i;
    } else if (c < 0x20 || c == 0x7f) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      out += buffer;
      ++i;
    } else if (c < 0x80) {
      out += static_cast<char>(c);
      ++i;
    } else {
      size_t length = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
      bool valid = length > 0 && c < 0xf5 && i + length <= text.size();
      for (size_t k = 1; valid && k < length; ++k) {
        valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
      }
      if (valid) {
        out.append(text, i, length);
        i += length;
      } else {
        out += "\\ufffd";
        ++i;
      }
    }
  }
  return out + "\"";
}

std::string Number(double value) {
  if (!std::isfinite(value)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

template <typename Pose>
std::string PoseJson(const Pose &pose) {
  auto euler = pose.Rot().Euler();
  return "[" + Number(pose.Pos().X()) + ", " + Number(pose.Pos().Y()) + ", " +
         Number(pose.Pos().Z()) + ", " + Number(euler.X()) + ", " +
         Number(euler.Y()) + ", " + Number(euler.Z()) + "]";
}

const char *JointTypeName(sdf::JointType type) {
  switch (type) {
    case sdf::JointType::BALL: return "ball";
    case sdf::JointType::CONTINUOUS: return "continuous";
    case sdf::JointType::FIXED: return "fixed";
    case sdf::JointType::GEARBOX: return "gearbox";
    case sdf::JointType::PRISMATIC: return "prismatic";
    case sdf::JointType::REVOLUTE: return "revolute";
    case sdf::JointType::REVOLUTE2: return "revolute2";
    case sdf::JointType::SCREW: return "screw";
    case sdf::JointType::UNIVERSAL: return "universal";
    default: return "invalid";
  }
}

// One message libsdformat's console wrote: its level (Error, Warning, Dbg), where in
// libsdformat it was written (parser_urdf.cc:2648), and its text.
struct Message {
  std::string level, where, text;
};

// The console writes "\033[1;<colour>m<Level> [<file>:<line>]\033[0m <text>" for each
// message; split the captured stream back into messages.
std::vector<Message> SplitConsole(const std::string &captured) {
  std::vector<Message> messages;
  const std::string start = "\033[1;", end = "\033[0m ";
  size_t at = captured.find(start);
  while (at != std::string::npos) {
    size_t open = captured.find('m', at + start.size());
    size_t close = captured.find(end, at);
    size_t next = captured.find(start, at + start.size());
    if (open == std::string::npos || close == std::string::npos ||
        (next != std::string::npos && close > next)) {
      break;
    }
    std::string label = captured.substr(open + 1, close - open - 1);
    size_t bracket = label.find(" [");
    Message message;
    message.level = label.substr(0, bracket);
    if (bracket != std::string::npos && label.size() > bracket + 3) {
      message.where = label.substr(bracket + 2, label.size() - bracket - 3);
    }
    size_t body = close + end.size();
    message.text = captured.substr(
        body, (next == std::string::npos ? captured.size() : next) - body);
    while (!message.text.empty() &&
           (message.text.back() == '\n' || message.text.back() == ' ')) {
      message.text.pop_back();
    }
    messages.push_back(message);
    at = next;
  }
  return messages;
}

// urdfdom (through console_bridge) writes "Error:   <text>\n         at line N in F"
// on stderr; its messages, by level, without the source line that follows each.
std::vector<Message> SplitUrdfdom(const std::string &captured) {
  std::vector<Message> messages;
  std::istringstream lines(captured);
  std::string line;
  while (std::getline(lines, line)) {
    for (const char *level : {"Error", "Warning"}) {
      std::string prefix = std::string(level) + ":";
      if (line.compare(0, prefix.size(), prefix) == 0) {
        size_t text = line.find_first_not_of(' ', prefix.size());
        messages.push_back({level, "urdfdom",
                            text == std::string::npos ? "" : line.substr(text)});
      }
    }
  }
  return messages;
}

std::string MessagesJson(const std::vector<Message> &messages,
                         const std::string &level) {
  std::string out = "[";
  for (const auto &message : messages) {
    if (message.level != level) continue;
    if (out.size() > 1) out += ", ";
    out += "{\"where\": " + Quote(message.where) + ", \"text\": " +
           Quote(Clip(message.text)) + "}";
  }
  return out + "]";
}

// The name between `before` and `after` in text, if text is exactly that.
bool NameBetween(const std::string &text, const std::string &before,
                 const std::string &after, std::string &name) {
  if (text.size() < before.size() + after.size() ||
      text.compare(0, before.size(), before) != 0 ||
      text.compare(text.size() - after.size(), after.size(), after) != 0) {
    return false;
  }
  name = text.substr(before.size(), text.size() - before.size() - after.size());
  return true;
}

// What libsdformat says it did to links, in its own words (a debug note in
// sdformat 12, a warning in later releases): lumped by a fixed joint into its parent,
// or left out with everything below it for want of mass.
std::string LinkFatesJson(const std::vector<Message> &messages) {
  std::string lumped = "[", dropped = "[";
  for (const auto &message : messages) {
    std::string name;
    const std::string &text = message.text;
    const std::string from = "Fixed Joint Reduction: extension lumping from [";
    size_t to = text.rfind("] to [");
    if (text.compare(0, from.size(), from) == 0 && to != std::string::npos &&
        to > from.size() && text.back() == ']') {
      if (lumped.size() > 1) lumped += ", ";
      lumped += "{\"link\": " + Quote(text.substr(from.size(), to - from.size())) +
                ", \"into\": " + Quote(text.substr(to + 6, text.size() - to - 7)) + "}";
    } else if (NameBetween(text, "urdf2sdf: link[", "] has no inertia, not modeled in sdf",
                           name) ||
               NameBetween(text, "urdf2sdf: link[", "] is not modeled in sdf.", name)) {
      if (dropped.size() > 1) dropped += ", ";
      dropped += "{\"link\": " + Quote(name) + ", \"text\": " + Quote(Clip(text)) + "}";
    }
  }
  return "\"lumped\": " + lumped + "], \"dropped\": " + dropped + "]";
}

std::string ModelJson(const sdf::Model &model) {
  std::string out = "{\"name\": " + Quote(model.Name()) +
                    ", \"canonical_link\": " + Quote(model.CanonicalLinkName()) +
                    ", \"links\": [";
  for (uint64_t i = 0; i < model.LinkCount(); ++i) {
    const sdf::Link *link = model.LinkByIndex(i);
    const auto &inertial = link->Inertial();
    const auto moi = inertial.Moi();  // about the centre of mass, link axes
    auto pose = link->RawPose();
    link->SemanticPose().Resolve(pose, "__model__");
    out += std::string(i ? ", " : "") + "{\"name\": " + Quote(link->Name()) +
           ", \"mass\": " + Number(inertial.MassMatrix().Mass()) +
           ", \"centre_of_mass\": [" + Number(inertial.Pose().Pos().X()) + ", " +
           Number(inertial.Pose().Pos().Y()) + ", " +
           Number(inertial.Pose().Pos().Z()) + "]" +
           ", \"inertia\": [" + Number(moi(0, 0)) + ", " + Number(moi(1, 1)) + ", " +
           Number(moi(2, 2)) + ", " + Number(moi(0, 1)) + ", " + Number(moi(0, 2)) +
           ", " + Number(moi(1, 2)) + "]" + ", \"pose\": " + PoseJson(pose) +
           ", \"collisions\": " + std::to_string(link->CollisionCount()) +
           ", \"visuals\": " + std::to_string(link->VisualCount()) +
           ", \"sensors\": " + std::to_string(link->SensorCount()) + "}";
  }
  out += "], \"joints\": [";
  for (uint64_t i = 0; i < model.JointCount(); ++i) {
    const sdf::Joint *joint = model.JointByIndex(i);
    out += std::string(i ? ", " : "") + "{\"name\": " + Quote(joint->Name()) +
           ", \"type\": " + Quote(JointTypeName(joint->Type())) +
           ", \"parent\": " + Quote(joint->ParentLinkName()) +
           ", \"child\": " + Quote(joint->ChildLinkName()) + "}";
  }
  out += "], \"frames\": [";
  for (uint64_t i = 0; i < model.FrameCount(); ++i) {
    const sdf::Frame *frame = model.FrameByIndex(i);
    std::string body;
    frame->ResolveAttachedToBody(body);
    out += std::string(i ? ", " : "") + "{\"name\": " + Quote(frame->Name()) +
           ", \"attached_to\": " + Quote(frame->AttachedTo()) +
           ", \"body\": " + Quote(body) + "}";
  }
  return out + "]}";
}

bool ReadAll(int fd, std::string &text) {
  char buffer[1 << 16];
  for (;;) {
    ssize_t got = read(fd, buffer, sizeof buffer);
    if (got == 0) return true;
    if (got < 0) return false;
    text.append(buffer, static_cast<size_t>(got));
    if (text.size() > kMaxInput) return false;
  }
}

// Everything written to fd since it was made (a memfd: no file in any folder).
std::string Captured(int fd) {
  std::string text;
  if (lseek(fd, 0, SEEK_SET) == 0) {
    char buffer[1 << 16];
    ssize_t got;
    while (text.size() < kMaxCaptured && (got = read(fd, buffer, sizeof buffer)) > 0) {
      text.append(buffer, static_cast<size_t>(got));
    }
  }
  return text;
}

bool WriteAll(int fd, const std::string &text) {
  size_t done = 0;
  while (done < text.size()) {
    ssize_t wrote = write(fd, text.data() + done, text.size() - done);
    if (wrote <= 0) return false;
    done += static_cast<size_t>(wrote);
  }
  return true;
}

// The system calls the helper may make once it is set up: memory, the files it
// already holds (stdin, stdout, the memfd), time, its own end. Everything else fails with
// EPERM: open, stat and access on any path (so nothing outside is read, and a missing
// file looks like a present one), execve, fork, socket. An allow-list, not a deny-list,
// so that a system call added to the kernel later is refused too.
const long kAllowed[] = {
    SYS_read, SYS_write, SYS_readv, SYS_writev, SYS_pread64, SYS_lseek, SYS_close,
    SYS_fstat, SYS_dup, SYS_dup3, SYS_fcntl, SYS_mmap, SYS_munmap, SYS_mremap,
    SYS_mprotect, SYS_madvise, SYS_brk, SYS_futex, SYS_getrandom, SYS_clock_gettime,
    SYS_gettimeofday, SYS_getpid, SYS_gettid, SYS_rt_sigreturn, SYS_rt_sigprocmask,
    SYS_rt_sigaction, SYS_sigaltstack, SYS_restart_syscall, SYS_sched_yield, SYS_exit,
    SYS_exit_group,
#ifdef SYS_dup2
    SYS_dup2,
#endif
};

#if defined(__x86_64__)
const unsigned kArch = AUDIT_ARCH_X86_64;
#elif defined(__aarch64__)
const unsigned kArch = AUDIT_ARCH_AARCH64;
#else
const unsigned kArch = 0;  // no filter written for this architecture: Confine refuses
#endif

// The low 32 bits of argument i (both architectures above are little-endian).
constexpr unsigned ArgLow(int i) {
  return offsetof(struct seccomp_data, args) + 8 * i;
}

// Install the filter for good (it outlives nothing: the helper execs nothing). False,
// with errno, when the kernel refuses it.
bool Confine() {
  if (kArch == 0) {
    errno = ENOSYS;
    return false;
  }
  const unsigned allow = SECCOMP_RET_ALLOW;
  const unsigned refuse = SECCOMP_RET_ERRNO | (EPERM & SECCOMP_RET_DATA);
  std::vector<sock_filter> program = {
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, arch)),
      BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, kArch, 1, 0),
      BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_KILL_PROCESS),  // another ABI's numbers
      BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
  };
#if defined(__x86_64__)
  // x32 system calls have other numbers with this bit set: refuse them all.
  program.push_back(BPF_JUMP(BPF_JMP | BPF_JGE | BPF_K, 0x40000000u, 0, 1));
  program.push_back(BPF_STMT(BPF_RET | BPF_K, refuse));
#endif
  for (long call : kAllowed) {
    program.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, unsigned(call), 0, 1));
    program.push_back(BPF_STMT(BPF_RET | BPF_K, allow));
  }
  // fstat is newfstatat(fd, "", AT_EMPTY_PATH) or statx(fd, "", AT_EMPTY_PATH) in
  // glibc: allowed on an open file only, never on a path.
  for (auto [call, flags] : {std::pair<long, int>{SYS_newfstatat, 3}, {SYS_statx, 2}}) {
    program.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, unsigned(call), 0, 4));
    program.push_back(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, ArgLow(flags)));
    program.push_back(BPF_JUMP(BPF_JMP | BPF_JSET | BPF_K, AT_EMPTY_PATH, 0, 1));
    program.push_back(BPF_STMT(BPF_RET | BPF_K, allow));
    program.push_back(BPF_STMT(BPF_RET | BPF_K, refuse));
  }
  // abort() signals the process itself (tgkill on its own pid): no other process.
  program.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, unsigned(SYS_tgkill), 0, 4));
  program.push_back(BPF_STMT(BPF_LD | BPF_W | BPF_ABS, ArgLow(0)));
  program.push_back(BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, unsigned(getpid()), 0, 1));
  program.push_back(BPF_STMT(BPF_RET | BPF_K, allow));
  program.push_back(BPF_STMT(BPF_RET | BPF_K, refuse));
  program.push_back(BPF_STMT(BPF_RET | BPF_K, refuse));
  sock_fprog filter = {static_cast<unsigned short>(program.size()), program.data()};
  return prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0 &&
         prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &filter, 0, 0) == 0;
}

}  // namespace

int main(int argc, char **argv) {
  bool with_sdf = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--sdf") == 0) {
      with_sdf = true;
    } else if (std::strcmp(argv[i], "--version") == 0) {
      std::printf("mcar-sdformat %d, libsdformat %s\n", kInterface, SDF_VERSION_FULL);
      return 0;
    } else {
      std::fprintf(stderr, "usage: mcar-sdformat [--sdf] < robot.urdf\n");
      return 2;
    }
  }
  std::string robot;
  if (!ReadAll(0, robot)) {
    std::fprintf(stderr, "mcar-sdformat: cannot read the robot from stdin\n");
    return 2;
  }
  // The answer goes to the real stdout. While libsdformat works, what any library
  // prints on stdout or stderr (urdfdom's errors, through console_bridge) is kept in
  // memory instead, and its errors and warnings become part of the answer.
  int answer = dup(1), saved_stderr = dup(2);
  int library_output = memfd_create("library-output", 0);
  if (answer < 0 || saved_stderr < 0 || library_output < 0 ||
      dup2(library_output, 1) < 0 || dup2(library_output, 2) < 0) {
    return 2;
  }

  // No log file: the console opens ~/.sdformat/sdformat.log when HOME is set.
  unsetenv("HOME");
  std::ostringstream swallowed;
  std::streambuf *stderr_buffer = std::cerr.rdbuf(swallowed.rdbuf());
  auto console = sdf::Console::Instance();  // says "No HOME defined" to std::cerr
  std::cerr.rdbuf(stderr_buffer);
  std::ostringstream captured;
  console->SetQuiet(false);
  console->GetMsgStream().SetStream(&captured);  // errors and warnings
  console->GetLogStream().SetStream(&captured);  // the debug notes

  // From here on the robot's text is read: no file opens any more (see Confine).
  if (!Confine()) {
    int error = errno;
    dup2(saved_stderr, 2);
    std::fprintf(stderr, "mcar-sdformat: cannot confine itself (seccomp: %s)\n",
                 std::strerror(error));
    return 2;
  }
  sdf::Root root;
  sdf::Errors errors = root.LoadSdfString(robot);
  std::string sdf_text;
  if (with_sdf && root.Element()) {
    sdf_text = root.Element()->ToString("");
  }
  console->GetMsgStream().SetStream(nullptr);
  console->GetLogStream().SetStream(nullptr);
  std::fflush(stdout);
  std::cout.flush();
  dup2(saved_stderr, 2);

  // urdfdom's words first: when it cannot read a URDF, libsdformat only says that.
  std::vector<Message> printed = SplitUrdfdom(Captured(library_output));
  for (const auto &message : SplitConsole(captured.str())) printed.push_back(message);
  std::vector<Message> verdict;
  for (const auto &error : errors) {
    verdict.push_back({"Error", "error code " +
                       std::to_string(static_cast<int>(error.Code())), error.Message()});
  }
  std::string out = "{\"interface\": " + std::to_string(kInterface) +
                    ", \"sdformat\": " + Quote(SDF_VERSION_FULL) +
                    ", \"errors\": " + MessagesJson(verdict, "Error") +
                    ", \"console_errors\": " + MessagesJson(printed, "Error") +
                    ", \"warnings\": " + MessagesJson(printed, "Warning") + ", " +
                    LinkFatesJson(printed) + ", \"model\": ";
  const sdf::Model *model = root.Model();
  out += model ? ModelJson(*model) : "null";
  if (with_sdf) out += ", \"sdf\": " + Quote(sdf_text);
  out += "}\n";
  return WriteAll(answer, out) ? 0 : 2;
}
