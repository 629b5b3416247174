// The harness image's link in QEMU (remote_link.hpp): QEMU started on a free
// loopback port, the image's serial port on the first connection to it.

#include <unistd.h>

#include "tests/ports/stm32f4/qemu_machine.hpp"
#include "tests/ports/stm32f4/remote_link.hpp"

namespace qemu_test
{

namespace
{

constexpr int answer_timeout_ms = 20000;

// The harness image, started by this link: it announces itself with an
// empty answer once it listens.
class QemuLink : public HarnessLink
{
  public:
    explicit QemuLink(bool icount)
      : machine_(QEMU_HARNESS_IMAGE, icount, Start::on_first_connection)
      , socket_(machine_.first_connection())
    {
        uint8_t ready[REMOTE_HEADER_BYTES];
        receive(ready, sizeof ready);
        if (ready[0] != REMOTE_ANSWER_MAGIC || ready[1] != REMOTE_OK || ready[2] || ready[3])
            fail("the image did not announce itself");
    }
    ~QemuLink() override
    {
        ::close(socket_);
    }
    void send(const uint8_t *bytes, size_t count) override
    {
        write_all(socket_, bytes, count);
    }
    void receive(uint8_t *bytes, size_t count) override
    {
        read_exactly(socket_, bytes, count, answer_timeout_ms);
    }

  private:
    QemuMachine machine_;
    int socket_;
};

} // namespace

std::unique_ptr<HarnessLink> open_harness_link(bool count_instructions)
{
    return std::make_unique<QemuLink>(count_instructions);
}

} // namespace qemu_test
