#ifndef MICHI_TOOLS_SRC_SVG_WRITER_
#define MICHI_TOOLS_SRC_SVG_WRITER_

// Private to michi_tools (not installed): SVG text output for writeProblemSvg() (SvgPlot.cpp).

#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            /** A number for SVG: fixed point, at most \e decimals digits, no trailing zeros, no "-0". */
            std::string num(double value, int decimals = 2);

            std::string escapeXml(const std::string &text);

            using Attributes = std::vector<std::pair<std::string, std::string>>;

            /** Writes well-formed SVG elements into a string; attribute values and text are escaped here. */
            class SvgWriter
            {
            public:
                SvgWriter(double width, double height)
                {
                    const std::string w = num(width, 0), h = num(height, 0);
                    open("svg", {{"xmlns", "http://www.w3.org/2000/svg"},
                                 {"width", w},
                                 {"height", h},
                                 {"viewBox", "0 0 " + w + " " + h},
                                 {"font-family", "DejaVu Sans, Arial, sans-serif"},
                                 {"font-size", "12"}});
                    element("rect", {{"width", w}, {"height", h}, {"fill", "white"}});
                }

                void open(const std::string &tag, const Attributes &attributes = {})
                {
                    indent();
                    out_ << '<' << tag;
                    writeAttributes(attributes);
                    out_ << ">\n";
                    open_.push_back(tag);
                }

                void close()
                {
                    const std::string tag = open_.back();
                    open_.pop_back();
                    indent();
                    out_ << "</" << tag << ">\n";
                }

                void element(const std::string &tag, const Attributes &attributes, const std::string &text = "")
                {
                    indent();
                    out_ << '<' << tag;
                    writeAttributes(attributes);
                    if (text.empty())
                        out_ << "/>\n";
                    else
                        out_ << '>' << escapeXml(text) << "</" << tag << ">\n";
                }

                void text(double x, double y, const std::string &content, Attributes attributes = {})
                {
                    attributes.insert(attributes.begin(), {{"x", num(x)}, {"y", num(y)}});
                    element("text", attributes, content);
                }

                /** The document, with every element still open closed. */
                std::string finish()
                {
                    while (!open_.empty())
                        close();
                    return out_.str();
                }

            private:
                void indent()
                {
                    for (std::size_t i = 0; i < open_.size(); ++i)
                        out_ << "  ";
                }

                void writeAttributes(const Attributes &attributes)
                {
                    for (const auto &a : attributes)
                        out_ << ' ' << a.first << "=\"" << escapeXml(a.second) << '"';
                }

                std::ostringstream out_;
                std::vector<std::string> open_;
            };
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi

#endif
