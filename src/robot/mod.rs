//! Soar-SLAM: the simulated Pioneer, its sonar, odometry drift and the Hough pipeline (issue 6).
