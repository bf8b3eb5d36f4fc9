// A fixture for tools/lint/function_length.py: one function of 125 lines, one of 3, a class
// with a short method and a lambda inside the long function (counted with it).
#include <string>

namespace fixture {

int Short(int x) { return x + 1; }

class Holder {
 public:
  int Get() const {
    return value_;
  }
 private:
  int value_{0};
};

int Long(int x) {
  auto twice = [](int v) {
    return 2 * v;
  };
  const std::string text = "a brace { in a string";
  // and one } in a comment
  x = twice(x) + 0;
  x = twice(x) + 1;
  x = twice(x) + 2;
  x = twice(x) + 3;
  x = twice(x) + 4;
  x = twice(x) + 5;
  x = twice(x) + 6;
  x = twice(x) + 7;
  x = twice(x) + 8;
  x = twice(x) + 9;
  x = twice(x) + 10;
  x = twice(x) + 11;
  x = twice(x) + 12;
  x = twice(x) + 13;
  x = twice(x) + 14;
  x = twice(x) + 15;
  x = twice(x) + 16;
  x = twice(x) + 17;
  x = twice(x) + 18;
  x = twice(x) + 19;
  x = twice(x) + 20;
  x = twice(x) + 21;
  x = twice(x) + 22;
  x = twice(x) + 23;
  x = twice(x) + 24;
  x = twice(x) + 25;
  x = twice(x) + 26;
  x = twice(x) + 27;
  x = twice(x) + 28;
  x = twice(x) + 29;
  x = twice(x) + 30;
  x = twice(x) + 31;
  x = twice(x) + 32;
  x = twice(x) + 33;
  x = twice(x) + 34;
  x = twice(x) + 35;
  x = twice(x) + 36;
  x = twice(x) + 37;
  x = twice(x) + 38;
  x = twice(x) + 39;
  x = twice(x) + 40;
  x = twice(x) + 41;
  x = twice(x) + 42;
  x = twice(x) + 43;
  x = twice(x) + 44;
  x = twice(x) + 45;
  x = twice(x) + 46;
  x = twice(x) + 47;
  x = twice(x) + 48;
  x = twice(x) + 49;
  x = twice(x) + 50;
  x = twice(x) + 51;
  x = twice(x) + 52;
  x = twice(x) + 53;
  x = twice(x) + 54;
  x = twice(x) + 55;
  x = twice(x) + 56;
  x = twice(x) + 57;
  x = twice(x) + 58;
  x = twice(x) + 59;
  x = twice(x) + 60;
  x = twice(x) + 61;
  x = twice(x) + 62;
  x = twice(x) + 63;
  x = twice(x) + 64;
  x = twice(x) + 65;
  x = twice(x) + 66;
  x = twice(x) + 67;
  x = twice(x) + 68;
  x = twice(x) + 69;
  x = twice(x) + 70;
  x = twice(x) + 71;
  x = twice(x) + 72;
  x = twice(x) + 73;
  x = twice(x) + 74;
  x = twice(x) + 75;
  x = twice(x) + 76;
  x = twice(x) + 77;
  x = twice(x) + 78;
  x = twice(x) + 79;
  x = twice(x) + 80;
  x = twice(x) + 81;
  x = twice(x) + 82;
  x = twice(x) + 83;
  x = twice(x) + 84;
  x = twice(x) + 85;
  x = twice(x) + 86;
  x = twice(x) + 87;
  x = twice(x) + 88;
  x = twice(x) + 89;
  x = twice(x) + 90;
  x = twice(x) + 91;
  x = twice(x) + 92;
  x = twice(x) + 93;
  x = twice(x) + 94;
  x = twice(x) + 95;
  x = twice(x) + 96;
  x = twice(x) + 97;
  x = twice(x) + 98;
  x = twice(x) + 99;
  x = twice(x) + 100;
  x = twice(x) + 101;
  x = twice(x) + 102;
  x = twice(x) + 103;
  x = twice(x) + 104;
  x = twice(x) + 105;
  x = twice(x) + 106;
  x = twice(x) + 107;
  x = twice(x) + 108;
  x = twice(x) + 109;
  x = twice(x) + 110;
  x = twice(x) + 111;
  x = twice(x) + 112;
  x = twice(x) + 113;
  x = twice(x) + 114;
  x = twice(x) + 115;
  x = twice(x) + 116;
  x = twice(x) + 117;
  return x;
}

}  // namespace fixture
