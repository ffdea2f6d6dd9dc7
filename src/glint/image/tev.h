#pragma once
// A live view: the image as it forms, streamed to a viewer speaking tev's TCP protocol (tev,
// and the protocol pbrt-v4 and Mitsuba use for their displays).
//
// Each packet is a little-endian u32 with the packet's whole length, a u8 type, then the fields:
// strings end in a zero byte, integers are little-endian. glint sends
//   CreateImage (4):    grab focus (u8), name, width, height (i32), channel count (i32), channel names
//   UpdateImageV3 (6):  grab focus, name, channel count, channel names, x, y, width, height (i32),
//                       per channel an offset then a stride (i64 each), then the floats
//   CloseImage (2):     name
// Updates go in strips of rows, each well under tev's packet limit.
//
// A viewer that is absent, refuses, stalls (5 s send timeout) or goes away is never an error:
// the client notes why once and stops sending; the render goes on.
#include <cstdint>
#include <string>
#include <vector>

#include "glint/film/film.h"

namespace glint {

class TevClient {
public:
    /// Connects to "HOST:PORT" (a 2 s timeout). On failure connected() is false and note() says why.
    explicit TevClient(const std::string& address);
    ~TevClient();
    TevClient(const TevClient&) = delete;
    TevClient& operator=(const TevClient&) = delete;

    bool connected() const { return fd_ >= 0; }
    /// Why the viewer was given up (empty while it is connected).
    const std::string& note() const { return note_; }

    /// Sends the film as image `name` (channels R, G, B): the first time closes any image of that
    /// name and creates it, then updates every pixel. Returns false (and closes) if the viewer cannot take it.
    bool send(const std::string& name, const Film& film);
    /// Closes the image in the viewer.
    void close_image(const std::string& name);

    // The packets, public for the test suite's receiver.
    static std::vector<char> create_image_packet(const std::string& name, int width, int height,
                                                 const std::vector<std::string>& channels);
    static std::vector<char> update_packet(const std::string& name, const Film& film, int row0, int rows);
    static std::vector<char> close_packet(const std::string& name);

private:
    bool write_all(const std::vector<char>& packet);
    void give_up(const std::string& why);
    int fd_ = -1;
    std::string address_, note_;
    bool created_ = false;
};

}  // namespace glint
