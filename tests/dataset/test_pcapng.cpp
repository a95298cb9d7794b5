// Captures in the other layouts tcpdump and Wireshark save: pcapng (Wireshark's default) in either
// byte order and time-stamp resolution, and libpcap written on a big-endian host or with
// nanosecond stamps, read as the same datagrams at the same times as their little-endian libpcap twin.
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

#include "ladarsim/core/input_error.h"
#include "ladarsim/dataset/pcap_udp.h"
#include "../support/pcap_writer.h"
#include "../support/scratch_dir.h"
#include "../support/udp_datagrams.h"

using namespace ladarsim;
using Catch::Matchers::Contains;
using test::Bytes;
using test::PcapRecord;
using test::datagrams;
using Seen = test::SeenDatagram;

namespace {

std::string error_of(const std::filesystem::path& file) {
    try {
        datagrams(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

/// Two datagrams, one of them in fragments sent out of order, at microseconds that no binary
/// fraction holds exactly.
std::vector<PcapRecord> traffic() {
    Bytes big(5000), small(48);
    for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<unsigned char>(i * 13);
    for (std::size_t i = 0; i < small.size(); ++i) small[i] = static_cast<unsigned char>(i + 1);
    auto fragments = test::udp_fragments(big, 7502, 9);
    std::vector<Bytes> sent(fragments.rbegin(), fragments.rend());
    sent.insert(sent.begin() + 1, test::udp_fragments(small, 2368, 10)[0]);
    std::vector<PcapRecord> r;
    for (std::size_t i = 0; i < sent.size(); ++i)
        r.push_back({1700000000, 123457 + 100003 * static_cast<std::uint32_t>(i), sent[i]});
    return r;
}

/// The file written as a big-endian host writes it, or with nanosecond stamps (the same instants).
void rewrite_pcap(const std::filesystem::path& from, const std::filesystem::path& to, bool big_endian, bool nanoseconds) {
    std::ifstream in(from, std::ios::binary);
    Bytes b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto get = [&](std::size_t o) { return std::uint32_t(b[o]) | std::uint32_t(b[o + 1]) << 8 | std::uint32_t(b[o + 2]) << 16 | std::uint32_t(b[o + 3]) << 24; };
    auto put = [&](std::size_t o, std::uint32_t v) {
        for (int i = 0; i < 4; ++i) b[o + static_cast<std::size_t>(i)] = static_cast<unsigned char>(v >> (big_endian ? 24 - 8 * i : 8 * i));
    };
    auto put16 = [&](std::size_t o, std::uint16_t v) {
        b[o] = static_cast<unsigned char>(big_endian ? v >> 8 : v);
        b[o + 1] = static_cast<unsigned char>(big_endian ? v : v >> 8);
    };
    const std::uint32_t header[] = {get(0), get(8), get(12), get(16), get(20)};
    put(0, nanoseconds ? 0xa1b23c4du : header[0]);
    put16(4, 2);
    put16(6, 4);
    for (std::size_t k = 1; k < 5; ++k) put(4 + 4 * k, header[k]);
    for (std::size_t off = 24; off < b.size();) {
        const std::uint32_t f[] = {get(off), get(off + 4), get(off + 8), get(off + 12)};
        put(off, f[0]);
        put(off + 4, nanoseconds ? f[1] * 1000 : f[1]);
        put(off + 8, f[2]);
        put(off + 12, f[3]);
        off += 16 + f[2];
    }
    std::ofstream(to, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

void check_same(const std::vector<Seen>& got, const std::vector<Seen>& want, double time_margin) {
    REQUIRE(got.size() == want.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        CHECK(got[i].record == want[i].record);
        CHECK(got[i].port == want[i].port);
        CHECK(got[i].payload == want[i].payload);
        if (time_margin == 0.0)
            CHECK(got[i].time_s == want[i].time_s);
        else
            CHECK(got[i].time_s == Approx(want[i].time_s).margin(time_margin));
    }
}

}  // namespace

TEST_CASE("a pcapng capture in either byte order gives the datagrams and times of its libpcap twin", "[pcap_udp]") {
    const test::ScratchDir dir;
    const auto records = traffic();
    test::write_pcap(dir / "twin.pcap", records);
    const auto want = datagrams(dir / "twin.pcap");
    REQUIRE(want.size() == 2);
    // Two sections (the second in the other byte order), with blocks a reader passes over.
    for (const bool big : {false, true}) {
        test::write_pcapng(dir / "c.pcapng", records, {.big_endian = big});
        check_same(datagrams(dir / "c.pcapng"), want, 0.0);
    }
    // Nanosecond stamps (if_tsresol 9): the same instants.
    test::write_pcapng(dir / "ns.pcapng", records, {.nanoseconds = 1});
    check_same(datagrams(dir / "ns.pcapng"), want, 1e-9);
    // The packet blocks of pcapng 1.0, which older tools still write.
    test::write_pcapng(dir / "old.pcapng", records, {.big_endian = true, .obsolete_packets = true});
    check_same(datagrams(dir / "old.pcapng"), want, 0.0);
}

TEST_CASE("a libpcap capture written on a big-endian host or with nanosecond stamps reads as its twin", "[pcap_udp]") {
    const test::ScratchDir dir;
    test::write_pcap(dir / "twin.pcap", traffic());
    const auto want = datagrams(dir / "twin.pcap");
    rewrite_pcap(dir / "twin.pcap", dir / "big.pcap", true, false);
    check_same(datagrams(dir / "big.pcap"), want, 0.0);
    rewrite_pcap(dir / "twin.pcap", dir / "ns.pcap", false, true);
    check_same(datagrams(dir / "ns.pcap"), want, 1e-9);
    rewrite_pcap(dir / "twin.pcap", dir / "big_ns.pcap", true, true);
    check_same(datagrams(dir / "big_ns.pcap"), want, 1e-9);
}

TEST_CASE("a pcapng capture ladarsim cannot read is one InputError naming the block or record", "[pcap_udp]") {
    const test::ScratchDir dir;
    const auto records = traffic();
    test::write_pcapng(dir / "raw_ip.pcapng", records, {.link_type = 101});
    CHECK_THAT(error_of(dir / "raw_ip.pcapng"), Contains("raw_ip.pcapng: record 1: interface 0's link type is not Ethernet"));
    test::write_pcapng(dir / "simple.pcapng", records, {.simple_packets = true});
    CHECK_THAT(error_of(dir / "simple.pcapng"), Contains("simple packet block carries no capture time"));
    test::write_pcapng(dir / "cut.pcapng", records);
    std::filesystem::resize_file(dir / "cut.pcapng", std::filesystem::file_size(dir / "cut.pcapng") - 30);
    CHECK_THAT(error_of(dir / "cut.pcapng"), Contains("capture ends inside a block"));
    std::ofstream(dir / "text.pcapng") << "\x0a\x0d\x0d\x0a but no byte-order magic after it";
    CHECK_THAT(error_of(dir / "text.pcapng"), Contains("byte-order magic"));
    std::ofstream(dir / "text.pcap") << "not a capture at all, just text";
    CHECK_THAT(error_of(dir / "text.pcap"), Contains("text.pcap: magic: neither a libpcap nor a pcapng capture"));
}
