#include "cluster/mpi_session.hpp"

#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

#include "core/error.hpp"

namespace spreadmap::cluster {
namespace {

constexpr auto poll_interval = std::chrono::milliseconds(10);

void check(int rc, const char *what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING] = {};
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw RunFailure(std::string("MPI: ") + what + ": " + text);
}

}  // namespace

MpiSession::MpiSession() {
  int ready = 0;
  MPI_Initialized(&ready);
  if (!ready) {
    // Only the main thread calls MPI; the cases' OpenMP threads never do.
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  // The ranks sharing this node's CPUs, less rank 0 when it only hands out cases.
  MPI_Comm node;
  check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node), "MPI_Comm_split_type");
  int on_node = 1, dispatcher_here = 0;
  const int is_dispatcher = rank_ == 0 && size_ > 1 ? 1 : 0;
  MPI_Comm_size(node, &on_node);
  MPI_Allreduce(&is_dispatcher, &dispatcher_here, 1, MPI_INT, MPI_SUM, node);
  MPI_Comm_free(&node);
  computing_on_node_ = std::max(1, on_node - dispatcher_here);
}

MpiSession::~MpiSession() {
  try {
    finish();
  } catch (...) {
  }
}

void MpiSession::finish() {
  if (finished_) return;
  finished_ = true;
  MPI_Finalize();
}

void MpiSession::send(int to, MpiTag tag, const std::string &text) {
  check(MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD), "MPI_Send");
}

std::optional<MpiMessage> MpiSession::poll(int source, int tag) {
  int flag = 0;
  MPI_Status status;
  check(MPI_Iprobe(source < 0 ? MPI_ANY_SOURCE : source, tag < 0 ? MPI_ANY_TAG : tag, MPI_COMM_WORLD, &flag, &status),
        "MPI_Iprobe");
  if (!flag) return std::nullopt;
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  MpiMessage m{status.MPI_SOURCE, status.MPI_TAG, std::string(static_cast<std::size_t>(count), '\0')};
  check(MPI_Recv(m.text.data(), count, MPI_CHAR, m.source, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return m;
}

MpiMessage MpiSession::wait(int source, int tag) {
  for (;;) {
    if (auto m = poll(source, tag)) return *m;
    std::this_thread::sleep_for(poll_interval);
  }
}

}  // namespace spreadmap::cluster
