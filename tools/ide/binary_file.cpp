// .abo files (aesl.md §6) with the node's own CRC-16/XMODEM.

#include "binary_file.hpp"

extern "C" {
#include "vm/node.h"
}

namespace aseba::ide
{

namespace
{

// CRC-16/XMODEM fed the way protocol.md §9 says: words low byte first,
// strings as UTF-8 padded with a zero byte to an even length.
class Crc
{
  public:
    void word(uint16_t value)
    {
        uint8_t bytes[2] = { uint8_t(value & 0xFF), uint8_t(value >> 8) };
        crc_ = node_crc16(crc_, bytes, 2);
    }
    void text(const std::string &value)
    {
        crc_ =
          node_crc16(crc_, reinterpret_cast<const uint8_t *>(value.data()), uint16_t(value.size()));
        if (value.size() % 2 != 0) {
            uint8_t zero = 0;
            crc_ = node_crc16(crc_, &zero, 1);
        }
    }
    uint16_t value() const
    {
        return crc_;
    }

  private:
    uint16_t crc_ = 0;
};

void append_word(std::vector<uint8_t> &bytes, uint16_t value)
{
    bytes.push_back(uint8_t(value & 0xFF));
    bytes.push_back(uint8_t(value >> 8));
}

} // namespace

uint16_t description_fingerprint(const TargetDescription &description)
{
    Crc crc;
    crc.word(description.bytecode_size);
    crc.word(description.variables_size);
    crc.word(description.stack_size);
    for (const NamedVariable &variable : description.named_variables) {
        crc.word(variable.size);
        crc.text(variable.name);
    }
    for (const LocalEvent &event : description.local_events)
        crc.text(event.name);
    for (const NativeFunction &function : description.native_functions) {
        crc.text(function.name);
        for (const NativeParameter &parameter : function.parameters) {
            crc.word(uint16_t(parameter.size));
            crc.text(parameter.name);
        }
    }
    return crc.value();
}

std::vector<uint8_t> binary_file(const TargetDescription &description,
                                 const BinaryIdentity &identity,
                                 const std::vector<uint16_t> &bytecode)
{
    std::vector<uint8_t> bytes = { 'A', 'B', 'O', 0 };
    append_word(bytes, 0); // file format version
    append_word(bytes, description.protocol_version);
    append_word(bytes, identity.product_id);
    append_word(bytes, identity.firmware_version);
    append_word(bytes, identity.node_id);
    Crc name;
    name.text(description.name);
    append_word(bytes, name.value());
    append_word(bytes, description_fingerprint(description));
    append_word(bytes, uint16_t(bytecode.size()));
    Crc code;
    for (uint16_t word : bytecode) {
        append_word(bytes, word);
        code.word(word);
    }
    append_word(bytes, code.value());
    return bytes;
}

std::string base64(const std::vector<uint8_t> &bytes)
{
    static const char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t group = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size())
            group |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size())
            group |= bytes[i + 2];
        text += alphabet[(group >> 18) & 63];
        text += alphabet[(group >> 12) & 63];
        text += i + 1 < bytes.size() ? alphabet[(group >> 6) & 63] : '=';
        text += i + 2 < bytes.size() ? alphabet[group & 63] : '=';
    }
    return text;
}

} // namespace aseba::ide
