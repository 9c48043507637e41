#include "SvgWriter.h"

#include <charconv>
#include <cmath>

namespace michi
{
    namespace tools
    {
        namespace svg_plot
        {
            std::string num(double value, int decimals)
            {
                const double unit = std::pow(10., decimals);
                value = std::round(value * unit) / unit;
                if (value == 0.)
                    value = 0.;  // drops the sign of -0
                char buffer[64];
                const auto result =
                    // to_chars, not a stream: no locale can turn the decimal point into a comma in the SVG.
                    std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed, decimals);
                std::string text(buffer, result.ptr);
                if (text.find('.') != std::string::npos)
                {
                    // Trailing zeros dropped: pictures with thousands of coordinates stay small.
                    while (text.back() == '0')
                        text.pop_back();
                    if (text.back() == '.')
                        text.pop_back();
                }
                return text;
            }

            std::string escapeXml(const std::string &text)
            {
                std::string escaped;
                for (char c : text)
                    switch (c)
                    {
                        case '&':
                            escaped += "&amp;";
                            break;
                        case '<':
                            escaped += "&lt;";
                            break;
                        case '>':
                            escaped += "&gt;";
                            break;
                        case '"':
                            escaped += "&quot;";
                            break;
                        // Single quotes too, so the text is safe in an attribute value quoted either way.
                        case '\'':
                            escaped += "&apos;";
                            break;
                        default:
                            escaped += c;
                    }
                return escaped;
            }
        }  // namespace svg_plot
    }      // namespace tools
}  // namespace michi
