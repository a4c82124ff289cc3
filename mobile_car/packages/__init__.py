"""Where things are: ROS package search ($(find), package://), the robot files of a
package, and the bundled mobile_car_description."""
