// MPI for the lifetime of one `spreadmap run --executor mpi`: initialised on construction,
// finalised by finish() or the destructor. Messages are JSON texts with a tag. Waiting is polling
// with short sleeps, never MPI's busy-waiting receive: rank 0 mostly waits, and must not take a
// core from the ranks that compute.
#pragma once
#include <optional>
#include <string>

namespace spreadmap::cluster {

enum MpiTag : int {
  tag_ask = 1,   // worker -> rank 0: "give me a case"; carries the outcome of the last one, or ""
  tag_work = 2,  // rank 0 -> worker: a CaseJob
  tag_stop = 3,  // rank 0 -> worker: no more cases, exit
};

struct MpiMessage {
  int source = -1;
  int tag = 0;
  std::string text;
};

class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession &) = delete;
  MpiSession &operator=(const MpiSession &) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Ranks on this node that run cases (rank 0 only hands them out when there are others).
  int computing_ranks_on_node() const { return computing_on_node_; }

  void send(int to, MpiTag tag, const std::string &text);
  // A message from `source` (-1: any) with `tag` (-1: any), if one has arrived.
  std::optional<MpiMessage> poll(int source, int tag);
  // Waits for one, sleeping between polls.
  MpiMessage wait(int source, int tag);

  // MPI_Finalize, once: after it no rank may talk to another.
  void finish();

 private:
  int rank_ = 0, size_ = 1, computing_on_node_ = 1;
  bool finished_ = false;
};

}  // namespace spreadmap::cluster
