// libglint_mpi.so: glint's Transport on MPI (mpi_module.h). Every call is made by the thread
// that initialised MPI.
#include <dlfcn.h>
#include <fmt/format.h>
#include <mpi.h>

#include <climits>
#include <list>

#include <stdexcept>
#include "glint/render/mpi_module.h"

namespace glint {
namespace {

class MpiTransport final : public Transport {
public:
    MpiTransport(int* argc, char*** argv) {
        // Open MPI loads its components with dlopen; they expect libmpi's symbols to be global,
        // and this module was itself loaded with RTLD_LOCAL.
        dlopen("libmpi.so.40", RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
        int provided = 0;
        if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
            throw std::runtime_error("MPI_Init_thread failed");
        MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
        MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
        MPI_Comm_size(MPI_COMM_WORLD, &size_);
    }
    ~MpiTransport() override {
        flush();
        MPI_Finalize();
    }
    int rank() const override { return rank_; }
    int size() const override { return size_; }

    void send(int to, int tag, std::vector<std::uint8_t> bytes) override {
        if (bytes.size() > static_cast<std::size_t>(INT_MAX))
            throw std::runtime_error(fmt::format("a message of {} bytes: more than MPI sends at once (the image is too large "
                                      "for a distributed render)", bytes.size()));
        Pending& p = pending_.emplace_back();
        p.bytes = std::move(bytes);
        check(MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD,
                        &p.request),
              "MPI_Isend");
        reap();
    }

    bool receive(Message& m) override {
        reap();
        int flag = 0;
        MPI_Status status;
        check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
        if (!flag) return false;
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        m.source = status.MPI_SOURCE;
        m.tag = status.MPI_TAG;
        m.bytes.resize(static_cast<std::size_t>(count));
        check(MPI_Recv(m.bytes.data(), count, MPI_BYTE, m.source, m.tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        return true;
    }

    void flush() override {
        for (Pending& p : pending_) MPI_Wait(&p.request, MPI_STATUS_IGNORE);
        pending_.clear();
    }

    [[noreturn]] void abort(int status) override {
        MPI_Abort(MPI_COMM_WORLD, status);
        std::abort();
    }

private:
    struct Pending {
        std::vector<std::uint8_t> bytes;
        MPI_Request request = MPI_REQUEST_NULL;
    };
    static void check(int code, const char* what) {
        if (code == MPI_SUCCESS) return;
        char text[MPI_MAX_ERROR_STRING] = {};
        int length = 0;
        MPI_Error_string(code, text, &length);
        throw std::runtime_error(fmt::format("{} failed: {}", what, text));
    }
    // Frees the buffers of sends that completed.
    void reap() {
        for (auto it = pending_.begin(); it != pending_.end();) {
            int done = 0;
            MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
            it = done ? pending_.erase(it) : std::next(it);
        }
    }
    int rank_ = 0, size_ = 1;
    std::list<Pending> pending_;  // a list: the buffers must not move while MPI reads them
};

Transport* create(int* argc, char*** argv) { return new MpiTransport(argc, argv); }

const MpiModule kModule{kMpiModuleAbi, &create};

}  // namespace
}  // namespace glint

extern "C" [[gnu::visibility("default")]] const glint::MpiModule* glint_mpi_module() { return &glint::kModule; }
