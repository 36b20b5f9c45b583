use kinloop::mechanism;

// 257 unknowns, each solved alone (257 blocks): one more than the determinant signs can track.
mechanism! {
    pub struct TooManyBlocks {
        input phi;
        unknowns s0 = 1, s1 = 1, s2 = 1, s3 = 1, s4 = 1, s5 = 1, s6 = 1, s7 = 1, s8 = 1, s9 = 1, s10 = 1, s11 = 1,
            s12 = 1, s13 = 1, s14 = 1, s15 = 1, s16 = 1, s17 = 1, s18 = 1, s19 = 1, s20 = 1, s21 = 1, s22 = 1, s23 = 1,
            s24 = 1, s25 = 1, s26 = 1, s27 = 1, s28 = 1, s29 = 1, s30 = 1, s31 = 1, s32 = 1, s33 = 1, s34 = 1, s35 = 1,
            s36 = 1, s37 = 1, s38 = 1, s39 = 1, s40 = 1, s41 = 1, s42 = 1, s43 = 1, s44 = 1, s45 = 1, s46 = 1, s47 = 1,
            s48 = 1, s49 = 1, s50 = 1, s51 = 1, s52 = 1, s53 = 1, s54 = 1, s55 = 1, s56 = 1, s57 = 1, s58 = 1, s59 = 1,
            s60 = 1, s61 = 1, s62 = 1, s63 = 1, s64 = 1, s65 = 1, s66 = 1, s67 = 1, s68 = 1, s69 = 1, s70 = 1, s71 = 1,
            s72 = 1, s73 = 1, s74 = 1, s75 = 1, s76 = 1, s77 = 1, s78 = 1, s79 = 1, s80 = 1, s81 = 1, s82 = 1, s83 = 1,
            s84 = 1, s85 = 1, s86 = 1, s87 = 1, s88 = 1, s89 = 1, s90 = 1, s91 = 1, s92 = 1, s93 = 1, s94 = 1, s95 = 1,
            s96 = 1, s97 = 1, s98 = 1, s99 = 1, s100 = 1, s101 = 1, s102 = 1, s103 = 1, s104 = 1, s105 = 1, s106 = 1, s107 = 1,
            s108 = 1, s109 = 1, s110 = 1, s111 = 1, s112 = 1, s113 = 1, s114 = 1, s115 = 1, s116 = 1, s117 = 1, s118 = 1, s119 = 1,
            s120 = 1, s121 = 1, s122 = 1, s123 = 1, s124 = 1, s125 = 1, s126 = 1, s127 = 1, s128 = 1, s129 = 1, s130 = 1, s131 = 1,
            s132 = 1, s133 = 1, s134 = 1, s135 = 1, s136 = 1, s137 = 1, s138 = 1, s139 = 1, s140 = 1, s141 = 1, s142 = 1, s143 = 1,
            s144 = 1, s145 = 1, s146 = 1, s147 = 1, s148 = 1, s149 = 1, s150 = 1, s151 = 1, s152 = 1, s153 = 1, s154 = 1, s155 = 1,
            s156 = 1, s157 = 1, s158 = 1, s159 = 1, s160 = 1, s161 = 1, s162 = 1, s163 = 1, s164 = 1, s165 = 1, s166 = 1, s167 = 1,
            s168 = 1, s169 = 1, s170 = 1, s171 = 1, s172 = 1, s173 = 1, s174 = 1, s175 = 1, s176 = 1, s177 = 1, s178 = 1, s179 = 1,
            s180 = 1, s181 = 1, s182 = 1, s183 = 1, s184 = 1, s185 = 1, s186 = 1, s187 = 1, s188 = 1, s189 = 1, s190 = 1, s191 = 1,
            s192 = 1, s193 = 1, s194 = 1, s195 = 1, s196 = 1, s197 = 1, s198 = 1, s199 = 1, s200 = 1, s201 = 1, s202 = 1, s203 = 1,
            s204 = 1, s205 = 1, s206 = 1, s207 = 1, s208 = 1, s209 = 1, s210 = 1, s211 = 1, s212 = 1, s213 = 1, s214 = 1, s215 = 1,
            s216 = 1, s217 = 1, s218 = 1, s219 = 1, s220 = 1, s221 = 1, s222 = 1, s223 = 1, s224 = 1, s225 = 1, s226 = 1, s227 = 1,
            s228 = 1, s229 = 1, s230 = 1, s231 = 1, s232 = 1, s233 = 1, s234 = 1, s235 = 1, s236 = 1, s237 = 1, s238 = 1, s239 = 1,
            s240 = 1, s241 = 1, s242 = 1, s243 = 1, s244 = 1, s245 = 1, s246 = 1, s247 = 1, s248 = 1, s249 = 1, s250 = 1, s251 = 1,
            s252 = 1, s253 = 1, s254 = 1, s255 = 1, s256 = 1;
        eq e0: s0 * s0 == phi + 2;
        eq e1: s1 * s1 == phi + 3;
        eq e2: s2 * s2 == phi + 4;
        eq e3: s3 * s3 == phi + 5;
        eq e4: s4 * s4 == phi + 6;
        eq e5: s5 * s5 == phi + 7;
        eq e6: s6 * s6 == phi + 8;
        eq e7: s7 * s7 == phi + 9;
        eq e8: s8 * s8 == phi + 10;
        eq e9: s9 * s9 == phi + 11;
        eq e10: s10 * s10 == phi + 12;
        eq e11: s11 * s11 == phi + 13;
        eq e12: s12 * s12 == phi + 14;
        eq e13: s13 * s13 == phi + 15;
        eq e14: s14 * s14 == phi + 16;
        eq e15: s15 * s15 == phi + 17;
        eq e16: s16 * s16 == phi + 18;
        eq e17: s17 * s17 == phi + 19;
        eq e18: s18 * s18 == phi + 20;
        eq e19: s19 * s19 == phi + 21;
        eq e20: s20 * s20 == phi + 22;
        eq e21: s21 * s21 == phi + 23;
        eq e22: s22 * s22 == phi + 24;
        eq e23: s23 * s23 == phi + 25;
        eq e24: s24 * s24 == phi + 26;
        eq e25: s25 * s25 == phi + 27;
        eq e26: s26 * s26 == phi + 28;
        eq e27: s27 * s27 == phi + 29;
        eq e28: s28 * s28 == phi + 30;
        eq e29: s29 * s29 == phi + 31;
        eq e30: s30 * s30 == phi + 32;
        eq e31: s31 * s31 == phi + 33;
        eq e32: s32 * s32 == phi + 34;
        eq e33: s33 * s33 == phi + 35;
        eq e34: s34 * s34 == phi + 36;
        eq e35: s35 * s35 == phi + 37;
        eq e36: s36 * s36 == phi + 38;
        eq e37: s37 * s37 == phi + 39;
        eq e38: s38 * s38 == phi + 40;
        eq e39: s39 * s39 == phi + 41;
        eq e40: s40 * s40 == phi + 42;
        eq e41: s41 * s41 == phi + 43;
        eq e42: s42 * s42 == phi + 44;
        eq e43: s43 * s43 == phi + 45;
        eq e44: s44 * s44 == phi + 46;
        eq e45: s45 * s45 == phi + 47;
        eq e46: s46 * s46 == phi + 48;
        eq e47: s47 * s47 == phi + 49;
        eq e48: s48 * s48 == phi + 50;
        eq e49: s49 * s49 == phi + 51;
        eq e50: s50 * s50 == phi + 52;
        eq e51: s51 * s51 == phi + 53;
        eq e52: s52 * s52 == phi + 54;
        eq e53: s53 * s53 == phi + 55;
        eq e54: s54 * s54 == phi + 56;
        eq e55: s55 * s55 == phi + 57;
        eq e56: s56 * s56 == phi + 58;
        eq e57: s57 * s57 == phi + 59;
        eq e58: s58 * s58 == phi + 60;
        eq e59: s59 * s59 == phi + 61;
        eq e60: s60 * s60 == phi + 62;
        eq e61: s61 * s61 == phi + 63;
        eq e62: s62 * s62 == phi + 64;
        eq e63: s63 * s63 == phi + 65;
        eq e64: s64 * s64 == phi + 66;
        eq e65: s65 * s65 == phi + 67;
        eq e66: s66 * s66 == phi + 68;
        eq e67: s67 * s67 == phi + 69;
        eq e68: s68 * s68 == phi + 70;
        eq e69: s69 * s69 == phi + 71;
        eq e70: s70 * s70 == phi + 72;
        eq e71: s71 * s71 == phi + 73;
        eq e72: s72 * s72 == phi + 74;
        eq e73: s73 * s73 == phi + 75;
        eq e74: s74 * s74 == phi + 76;
        eq e75: s75 * s75 == phi + 77;
        eq e76: s76 * s76 == phi + 78;
        eq e77: s77 * s77 == phi + 79;
        eq e78: s78 * s78 == phi + 80;
        eq e79: s79 * s79 == phi + 81;
        eq e80: s80 * s80 == phi + 82;
        eq e81: s81 * s81 == phi + 83;
        eq e82: s82 * s82 == phi + 84;
        eq e83: s83 * s83 == phi + 85;
        eq e84: s84 * s84 == phi + 86;
        eq e85: s85 * s85 == phi + 87;
        eq e86: s86 * s86 == phi + 88;
        eq e87: s87 * s87 == phi + 89;
        eq e88: s88 * s88 == phi + 90;
        eq e89: s89 * s89 == phi + 91;
        eq e90: s90 * s90 == phi + 92;
        eq e91: s91 * s91 == phi + 93;
        eq e92: s92 * s92 == phi + 94;
        eq e93: s93 * s93 == phi + 95;
        eq e94: s94 * s94 == phi + 96;
        eq e95: s95 * s95 == phi + 97;
        eq e96: s96 * s96 == phi + 98;
        eq e97: s97 * s97 == phi + 99;
        eq e98: s98 * s98 == phi + 100;
        eq e99: s99 * s99 == phi + 101;
        eq e100: s100 * s100 == phi + 102;
        eq e101: s101 * s101 == phi + 103;
        eq e102: s102 * s102 == phi + 104;
        eq e103: s103 * s103 == phi + 105;
        eq e104: s104 * s104 == phi + 106;
        eq e105: s105 * s105 == phi + 107;
        eq e106: s106 * s106 == phi + 108;
        eq e107: s107 * s107 == phi + 109;
        eq e108: s108 * s108 == phi + 110;
        eq e109: s109 * s109 == phi + 111;
        eq e110: s110 * s110 == phi + 112;
        eq e111: s111 * s111 == phi + 113;
        eq e112: s112 * s112 == phi + 114;
        eq e113: s113 * s113 == phi + 115;
        eq e114: s114 * s114 == phi + 116;
        eq e115: s115 * s115 == phi + 117;
        eq e116: s116 * s116 == phi + 118;
        eq e117: s117 * s117 == phi + 119;
        eq e118: s118 * s118 == phi + 120;
        eq e119: s119 * s119 == phi + 121;
        eq e120: s120 * s120 == phi + 122;
        eq e121: s121 * s121 == phi + 123;
        eq e122: s122 * s122 == phi + 124;
        eq e123: s123 * s123 == phi + 125;
        eq e124: s124 * s124 == phi + 126;
        eq e125: s125 * s125 == phi + 127;
        eq e126: s126 * s126 == phi + 128;
        eq e127: s127 * s127 == phi + 129;
        eq e128: s128 * s128 == phi + 130;
        eq e129: s129 * s129 == phi + 131;
        eq e130: s130 * s130 == phi + 132;
        eq e131: s131 * s131 == phi + 133;
        eq e132: s132 * s132 == phi + 134;
        eq e133: s133 * s133 == phi + 135;
        eq e134: s134 * s134 == phi + 136;
        eq e135: s135 * s135 == phi + 137;
        eq e136: s136 * s136 == phi + 138;
        eq e137: s137 * s137 == phi + 139;
        eq e138: s138 * s138 == phi + 140;
        eq e139: s139 * s139 == phi + 141;
        eq e140: s140 * s140 == phi + 142;
        eq e141: s141 * s141 == phi + 143;
        eq e142: s142 * s142 == phi + 144;
        eq e143: s143 * s143 == phi + 145;
        eq e144: s144 * s144 == phi + 146;
        eq e145: s145 * s145 == phi + 147;
        eq e146: s146 * s146 == phi + 148;
        eq e147: s147 * s147 == phi + 149;
        eq e148: s148 * s148 == phi + 150;
        eq e149: s149 * s149 == phi + 151;
        eq e150: s150 * s150 == phi + 152;
        eq e151: s151 * s151 == phi + 153;
        eq e152: s152 * s152 == phi + 154;
        eq e153: s153 * s153 == phi + 155;
        eq e154: s154 * s154 == phi + 156;
        eq e155: s155 * s155 == phi + 157;
        eq e156: s156 * s156 == phi + 158;
        eq e157: s157 * s157 == phi + 159;
        eq e158: s158 * s158 == phi + 160;
        eq e159: s159 * s159 == phi + 161;
        eq e160: s160 * s160 == phi + 162;
        eq e161: s161 * s161 == phi + 163;
        eq e162: s162 * s162 == phi + 164;
        eq e163: s163 * s163 == phi + 165;
        eq e164: s164 * s164 == phi + 166;
        eq e165: s165 * s165 == phi + 167;
        eq e166: s166 * s166 == phi + 168;
        eq e167: s167 * s167 == phi + 169;
        eq e168: s168 * s168 == phi + 170;
        eq e169: s169 * s169 == phi + 171;
        eq e170: s170 * s170 == phi + 172;
        eq e171: s171 * s171 == phi + 173;
        eq e172: s172 * s172 == phi + 174;
        eq e173: s173 * s173 == phi + 175;
        eq e174: s174 * s174 == phi + 176;
        eq e175: s175 * s175 == phi + 177;
        eq e176: s176 * s176 == phi + 178;
        eq e177: s177 * s177 == phi + 179;
        eq e178: s178 * s178 == phi + 180;
        eq e179: s179 * s179 == phi + 181;
        eq e180: s180 * s180 == phi + 182;
        eq e181: s181 * s181 == phi + 183;
        eq e182: s182 * s182 == phi + 184;
        eq e183: s183 * s183 == phi + 185;
        eq e184: s184 * s184 == phi + 186;
        eq e185: s185 * s185 == phi + 187;
        eq e186: s186 * s186 == phi + 188;
        eq e187: s187 * s187 == phi + 189;
        eq e188: s188 * s188 == phi + 190;
        eq e189: s189 * s189 == phi + 191;
        eq e190: s190 * s190 == phi + 192;
        eq e191: s191 * s191 == phi + 193;
        eq e192: s192 * s192 == phi + 194;
        eq e193: s193 * s193 == phi + 195;
        eq e194: s194 * s194 == phi + 196;
        eq e195: s195 * s195 == phi + 197;
        eq e196: s196 * s196 == phi + 198;
        eq e197: s197 * s197 == phi + 199;
        eq e198: s198 * s198 == phi + 200;
        eq e199: s199 * s199 == phi + 201;
        eq e200: s200 * s200 == phi + 202;
        eq e201: s201 * s201 == phi + 203;
        eq e202: s202 * s202 == phi + 204;
        eq e203: s203 * s203 == phi + 205;
        eq e204: s204 * s204 == phi + 206;
        eq e205: s205 * s205 == phi + 207;
        eq e206: s206 * s206 == phi + 208;
        eq e207: s207 * s207 == phi + 209;
        eq e208: s208 * s208 == phi + 210;
        eq e209: s209 * s209 == phi + 211;
        eq e210: s210 * s210 == phi + 212;
        eq e211: s211 * s211 == phi + 213;
        eq e212: s212 * s212 == phi + 214;
        eq e213: s213 * s213 == phi + 215;
        eq e214: s214 * s214 == phi + 216;
        eq e215: s215 * s215 == phi + 217;
        eq e216: s216 * s216 == phi + 218;
        eq e217: s217 * s217 == phi + 219;
        eq e218: s218 * s218 == phi + 220;
        eq e219: s219 * s219 == phi + 221;
        eq e220: s220 * s220 == phi + 222;
        eq e221: s221 * s221 == phi + 223;
        eq e222: s222 * s222 == phi + 224;
        eq e223: s223 * s223 == phi + 225;
        eq e224: s224 * s224 == phi + 226;
        eq e225: s225 * s225 == phi + 227;
        eq e226: s226 * s226 == phi + 228;
        eq e227: s227 * s227 == phi + 229;
        eq e228: s228 * s228 == phi + 230;
        eq e229: s229 * s229 == phi + 231;
        eq e230: s230 * s230 == phi + 232;
        eq e231: s231 * s231 == phi + 233;
        eq e232: s232 * s232 == phi + 234;
        eq e233: s233 * s233 == phi + 235;
        eq e234: s234 * s234 == phi + 236;
        eq e235: s235 * s235 == phi + 237;
        eq e236: s236 * s236 == phi + 238;
        eq e237: s237 * s237 == phi + 239;
        eq e238: s238 * s238 == phi + 240;
        eq e239: s239 * s239 == phi + 241;
        eq e240: s240 * s240 == phi + 242;
        eq e241: s241 * s241 == phi + 243;
        eq e242: s242 * s242 == phi + 244;
        eq e243: s243 * s243 == phi + 245;
        eq e244: s244 * s244 == phi + 246;
        eq e245: s245 * s245 == phi + 247;
        eq e246: s246 * s246 == phi + 248;
        eq e247: s247 * s247 == phi + 249;
        eq e248: s248 * s248 == phi + 250;
        eq e249: s249 * s249 == phi + 251;
        eq e250: s250 * s250 == phi + 252;
        eq e251: s251 * s251 == phi + 253;
        eq e252: s252 * s252 == phi + 254;
        eq e253: s253 * s253 == phi + 255;
        eq e254: s254 * s254 == phi + 256;
        eq e255: s255 * s255 == phi + 257;
        eq e256: s256 * s256 == phi + 258;
    }
}

fn main() {}
